// Linear BVH construction (Karras 2012) as per-item steps, so the GPU runs them as kernels
// and the CPU as loops: Morton keys, the hierarchy from sorted keys, then bounds bottom-up.
// The bottom-up pass is also the refit for moved vertices.
#pragma once

#include "shared/Bvh.h"

#include <vector>

namespace linkgi
{
namespace bvh
{
/// Axis-aligned box; empty when lo > hi.
struct Box
{
  Vec3f lo{ 3.4e38f, 3.4e38f, 3.4e38f };
  Vec3f hi{ -3.4e38f, -3.4e38f, -3.4e38f };

  LINKGI_HOST_DEVICE void grow(const Vec3f& p)
  {
    lo = { minOf(lo.x, p.x), minOf(lo.y, p.y), minOf(lo.z, p.z) };
    hi = { maxOf(hi.x, p.x), maxOf(hi.y, p.y), maxOf(hi.z, p.z) };
  }
  /// Union; an empty b leaves the box as it is.
  LINKGI_HOST_DEVICE void grow(const Box& b)
  {
    lo = { minOf(lo.x, b.lo.x), minOf(lo.y, b.lo.y), minOf(lo.z, b.lo.z) };
    hi = { maxOf(hi.x, b.hi.x), maxOf(hi.y, b.hi.y), maxOf(hi.z, b.hi.z) };
  }
};

LINKGI_HOST_DEVICE inline int clz64(std::uint64_t x)
{
#if defined(__CUDA_ARCH__)
  return __clzll(static_cast<long long>(x));
#else
  return x == 0 ? 64 : __builtin_clzll(x);
#endif
}

LINKGI_HOST_DEVICE inline int clz32(std::uint32_t x)
{
#if defined(__CUDA_ARCH__)
  return __clz(static_cast<int>(x));
#else
  return x == 0 ? 32 : __builtin_clz(x);
#endif
}

/// Spreads the low 16 bits of x to every fourth bit.
LINKGI_HOST_DEVICE inline std::uint64_t spreadBits16(std::uint64_t x)
{
  x &= 0xffffull;
  x = (x | x << 24) & 0x000000ff000000ffull;
  x = (x | x << 12) & 0x000f000f000f000full;
  x = (x | x << 6) & 0x0303030303030303ull;
  x = (x | x << 3) & 0x1111111111111111ull;
  return x;
}

/// Size-extended 64-bit Morton code of a triangle (Vinkler et al. 2017): the centroid of its
/// box within the scene box, and the box's diagonal (per axis relative to the scene's) as a
/// fourth dimension, 16 bits each, size first at every level. Large triangles then sort apart
/// from the small ones around their centre, which a 3D code mixes them with: conference's
/// linear BVH cost (summed child box areas over the root's) drops from 60.9 to 53.1, iphi's
/// from 63.5 to 53.8, tearoom's from 49.0 to 41.2 (binned SAH: 44.2, 45.8, 36.6).
LINKGI_HOST_DEVICE inline std::uint64_t mortonKey(const Vec3f& a, const Vec3f& b, const Vec3f& c,
  const Vec3f& sceneLo, const Vec3f& sceneInvExtent)
{
  const Vec3f lo(minOf(a.x, minOf(b.x, c.x)), minOf(a.y, minOf(b.y, c.y)), minOf(a.z, minOf(b.z, c.z)));
  const Vec3f hi(maxOf(a.x, maxOf(b.x, c.x)), maxOf(a.y, maxOf(b.y, c.y)), maxOf(a.z, maxOf(b.z, c.z)));
  const float scale = 65535.f; // 2^16 - 1
  const auto quantize = [&](float unit) {
    return static_cast<std::uint64_t>(fminf(fmaxf(unit * scale, 0.f), scale));
  };
  const Vec3f centre = (lo + hi) * 0.5f;
  const Vec3f extent((hi.x - lo.x) * sceneInvExtent.x, (hi.y - lo.y) * sceneInvExtent.y,
    (hi.z - lo.z) * sceneInvExtent.z);
  const float size = sqrtf(dot(extent, extent) * (1.f / 3.f)); // 1 for the scene box
  return spreadBits16(quantize(size)) << 3 |
    spreadBits16(quantize((centre.x - sceneLo.x) * sceneInvExtent.x)) << 2 |
    spreadBits16(quantize((centre.y - sceneLo.y) * sceneInvExtent.y)) << 1 |
    spreadBits16(quantize((centre.z - sceneLo.z) * sceneInvExtent.z));
}

/// Common-prefix length of sorted keys i and j, tie-broken by index so equal keys still
/// form a binary tree; -1 outside [0, n).
LINKGI_HOST_DEVICE inline int commonPrefix(const std::uint64_t* keys, int n, int i, int j)
{
  if (j < 0 || j >= n)
  {
    return -1;
  }
  const std::uint64_t a = keys[i], b = keys[j];
  return a == b ? 64 + clz32(static_cast<std::uint32_t>(i ^ j)) : clz64(a ^ b);
}

/// Karras 2012, one internal node i of n - 1: finds the key range it covers and where that
/// range splits, and links its two children (and their parents).
LINKGI_HOST_DEVICE inline void buildInternalNode(const std::uint64_t* keys, int n, int i,
  BvhNode* nodes, int* leafParents)
{
  const int d = commonPrefix(keys, n, i, i + 1) - commonPrefix(keys, n, i, i - 1) >= 0 ? 1 : -1;
  const int minPrefix = commonPrefix(keys, n, i, i - d);
  int maxLength = 2;
  while (commonPrefix(keys, n, i, i + maxLength * d) > minPrefix)
  {
    maxLength *= 2;
  }
  int length = 0;
  for (int t = maxLength / 2; t >= 1; t /= 2)
  {
    if (commonPrefix(keys, n, i, i + (length + t) * d) > minPrefix)
    {
      length += t;
    }
  }
  const int j = i + length * d;
  const int nodePrefix = commonPrefix(keys, n, i, j);
  int split = 0;
  for (int t = length;;)
  {
    t = (t + 1) / 2;
    if (commonPrefix(keys, n, i, i + (split + t) * d) > nodePrefix)
    {
      split += t;
    }
    if (t <= 1)
    {
      break;
    }
  }
  const int gamma = i + split * d + (d < 0 ? -1 : 0);
  const int first = i < j ? i : j, last = i < j ? j : i;
  BvhNode& node = nodes[i];
  node.child[0] = first == gamma ? ~gamma : gamma;
  node.child[1] = last == gamma + 1 ? ~(gamma + 1) : gamma + 1;
  for (int c = 0; c < 2; ++c)
  {
    if (node.child[c] < 0)
    {
      leafParents[~node.child[c]] = i;
    }
    else
    {
      nodes[node.child[c]].parent = i;
    }
  }
  if (i == 0)
  {
    node.parent = -1;
  }
}

/// The leaf-order triangle record of original triangle `id`.
LINKGI_HOST_DEVICE inline BvhTriangle makeTriangle(const Vec3f& a, const Vec3f& b, const Vec3f& c, Index id)
{
  return BvhTriangle{ a, id, b - a, 0.f, c - a, 0.f };
}

LINKGI_HOST_DEVICE inline Box triangleBox(const BvhTriangle& t)
{
  Box box;
  box.grow(t.v0);
  box.grow(t.v0 + t.e1);
  box.grow(t.v0 + t.e2);
  return box;
}

LINKGI_HOST_DEVICE inline void storeChildBox(BvhNode& node, int side, const Box& b)
{
  if (side == 0)
  {
    node.lo0x = b.lo.x, node.hi0x = b.hi.x, node.lo0y = b.lo.y, node.hi0y = b.hi.y;
    node.lo0z = b.lo.z, node.hi0z = b.hi.z;
  }
  else
  {
    node.lo1x = b.lo.x, node.hi1x = b.hi.x, node.lo1y = b.lo.y, node.hi1y = b.hi.y;
    node.lo1z = b.lo.z, node.hi1z = b.hi.z;
  }
}

/// Reads a float that another GPU thread may have just written (bypassing L1).
LINKGI_HOST_DEVICE inline float loadFresh(const float* p)
{
#if defined(__CUDA_ARCH__)
  return __ldcg(p);
#else
  return *p;
#endif
}

LINKGI_HOST_DEVICE inline Box unionOfChildren(const BvhNode& node)
{
  Box b;
  b.lo = { fminf(loadFresh(&node.lo0x), loadFresh(&node.lo1x)),
    fminf(loadFresh(&node.lo0y), loadFresh(&node.lo1y)),
    fminf(loadFresh(&node.lo0z), loadFresh(&node.lo1z)) };
  b.hi = { fmaxf(loadFresh(&node.hi0x), loadFresh(&node.hi1x)),
    fmaxf(loadFresh(&node.hi0y), loadFresh(&node.hi1y)),
    fmaxf(loadFresh(&node.hi0z), loadFresh(&node.hi1z)) };
  return b;
}

/// Returns the previous value of *counter after adding 1 (atomically on the GPU).
LINKGI_HOST_DEVICE inline unsigned arriveAt(unsigned* counter)
{
#if defined(__CUDA_ARCH__)
  __threadfence(); // our child box must be visible before the sibling reads it
  return atomicAdd(counter, 1u);
#else
  return __atomic_fetch_add(counter, 1u, __ATOMIC_ACQ_REL);
#endif
}

/// Bottom-up bounds from leaf `leaf`: writes its box into its parent, and the second thread
/// to arrive at a node carries the union on upwards. `arrivals` (n - 1 zeros) is consumed.
LINKGI_HOST_DEVICE inline void propagateBounds(BvhNode* nodes, const int* leafParents,
  const BvhTriangle* tris, unsigned* arrivals, int leaf)
{
  int child = ~leaf;
  int node = leafParents[leaf];
  Box box = triangleBox(tris[leaf]);
  while (node >= 0)
  {
    storeChildBox(nodes[node], nodes[node].child[0] == child ? 0 : 1, box);
    if (arriveAt(&arrivals[node]) == 0)
    {
      return; // the sibling subtree is not done; its thread continues from here
    }
#if defined(__CUDA_ARCH__)
    __threadfence();
#endif
    box = unionOfChildren(nodes[node]);
    child = node;
    node = nodes[node].parent;
  }
}
}

/// A BVH built on the CPU with the same steps the GPU runs, in the same layout; used by the
/// CPU ray tracer of builds without Embree, and by tests that check the GPU's layout.
struct HostBvh
{
  std::vector<BvhNode> nodes;
  std::vector<BvhTriangle> triangles;
  std::vector<int> leafParents;

  /// The linear BVH (Morton order), step for step as the GPU builds it.
  void build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles);
  /// A binned surface-area-heuristic tree instead (SahBuilder.cpp): slower to build,
  /// fewer nodes per ray.
  void buildSah(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles);
  /// New positions, same triangles as the last build.
  void refit(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles);
  BvhView view() const;
};
}
