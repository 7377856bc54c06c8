// The BVH that our own traversal reads, on the GPU and (without Embree) on the CPU: one
// node layout, one ray-box test, one ray-triangle test, one traversal loop for both.
#pragma once

#include "shared/RayTracer.h"

namespace linkgi
{
/// An internal node holding the boxes of both children (Aila & Laine 2009), so one 64-byte
/// fetch decides which children a ray enters. Four 16-byte words: child 0 xy, child 1 xy,
/// both z, then the child references.
struct alignas(16) BvhNode
{
  float lo0x, hi0x, lo0y, hi0y;
  float lo1x, hi1x, lo1y, hi1y;
  float lo0z, hi0z, lo1z, hi1z;
  /// >= 0: internal node index; < 0: ~(leaf position), one triangle per leaf.
  int child[2];
  int parent; ///< -1 at the root
  int pad;
};
static_assert(sizeof(BvhNode) == 64, "BvhNode must be four 16-byte words");

/// A triangle in leaf order, pre-transformed for Moeller-Trumbore: v0 and two edges.
/// Three 16-byte words; the original triangle index rides in the first word's w.
struct alignas(16) BvhTriangle
{
  Vec3f v0;
  Index id;
  Vec3f e1;
  float pad1;
  Vec3f e2;
  float pad2;
};
static_assert(sizeof(BvhTriangle) == 48, "BvhTriangle must be three 16-byte words");

/// What traversal needs: pointers into host or device memory.
struct BvhView
{
  const BvhNode* nodes = nullptr;
  const BvhTriangle* triangles = nullptr;
  int root = 0; ///< 0, or ~0 when the tree is a single leaf
  Index triangleCount = 0;
};

/// Traversal stack depth. LBVH depth is bounded by the 64 Morton key bits plus log2 of the
/// triangles sharing one code; deeper subtrees than this would be skipped, never crash.
constexpr int kBvhStackSize = 96;

namespace bvh
{
LINKGI_HOST_DEVICE inline BvhNode loadNode(const BvhNode* nodes, int i)
{
#if defined(__CUDA_ARCH__)
  // Read-only path: the node is fetched as four 16-byte words.
  const float4* p = reinterpret_cast<const float4*>(nodes + i);
  const float4 a = __ldg(p), b = __ldg(p + 1), c = __ldg(p + 2);
  const int4 d = __ldg(reinterpret_cast<const int4*>(p + 3));
  return BvhNode{ a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w, c.x, c.y, c.z, c.w, { d.x, d.y }, d.z, d.w };
#else
  return nodes[i];
#endif
}

LINKGI_HOST_DEVICE inline BvhTriangle loadTriangle(const BvhTriangle* tris, int i)
{
#if defined(__CUDA_ARCH__)
  const float4* p = reinterpret_cast<const float4*>(tris + i);
  const float4 a = __ldg(p), b = __ldg(p + 1), c = __ldg(p + 2);
  return BvhTriangle{ { a.x, a.y, a.z }, __float_as_uint(a.w), { b.x, b.y, b.z }, 0.f, { c.x, c.y, c.z }, 0.f };
#else
  return tris[i];
#endif
}

/// A ray prepared for slab tests: 1/d with tiny components replaced, so that an origin on a
/// slab plane gives +-inf instead of 0 * inf = NaN.
struct PreparedRay
{
  Vec3f origin, direction, invDir, originTimesInv;
  float tnear, tfar;
};

LINKGI_HOST_DEVICE inline float safeInverse(float d)
{
  const float kTiny = 1e-20f;
  return 1.f / (fabsf(d) > kTiny ? d : copysignf(kTiny, d));
}

LINKGI_HOST_DEVICE inline PreparedRay prepare(const Ray& r)
{
  PreparedRay p;
  p.origin = r.origin;
  p.direction = r.direction;
  p.invDir = { safeInverse(r.direction.x), safeInverse(r.direction.y), safeInverse(r.direction.z) };
  p.originTimesInv = { r.origin.x * p.invDir.x, r.origin.y * p.invDir.y, r.origin.z * p.invDir.z };
  p.tnear = r.tnear;
  p.tfar = r.tfar;
  return p;
}

/// min / max for the slab test: one instruction on the GPU; on the CPU a compare, because
/// the libm calls behind fminf cost more than the rest of the test (no NaNs arise here: 1/d
/// is finite).
LINKGI_HOST_DEVICE inline float minOf(float a, float b)
{
#if defined(__CUDA_ARCH__)
  return fminf(a, b);
#else
  return a < b ? a : b;
#endif
}
LINKGI_HOST_DEVICE inline float maxOf(float a, float b)
{
#if defined(__CUDA_ARCH__)
  return fmaxf(a, b);
#else
  return a > b ? a : b;
#endif
}

/// Entry distance of the ray into [lo, hi] if it enters before tfar, else a value > tfar.
LINKGI_HOST_DEVICE inline float slab(const PreparedRay& r, float tfar, float lox, float hix,
  float loy, float hiy, float loz, float hiz)
{
  const float x0 = lox * r.invDir.x - r.originTimesInv.x, x1 = hix * r.invDir.x - r.originTimesInv.x;
  const float y0 = loy * r.invDir.y - r.originTimesInv.y, y1 = hiy * r.invDir.y - r.originTimesInv.y;
  const float z0 = loz * r.invDir.z - r.originTimesInv.z, z1 = hiz * r.invDir.z - r.originTimesInv.z;
  const float tmin = maxOf(maxOf(minOf(x0, x1), minOf(y0, y1)), maxOf(minOf(z0, z1), r.tnear));
  const float tmax = minOf(minOf(maxOf(x0, x1), maxOf(y0, y1)), minOf(maxOf(z0, z1), tfar));
  return tmin <= tmax ? tmin : 3.4e38f;
}

/// Moeller-Trumbore; on a hit inside (tnear, tfar) sets t, u (weight of v1), v (of v2).
LINKGI_HOST_DEVICE inline bool intersectTriangle(const PreparedRay& r, const BvhTriangle& tri,
  float tfar, float& t, float& u, float& v)
{
  const Vec3f p = cross(r.direction, tri.e2);
  const float det = dot(tri.e1, p);
  if (det == 0.f)
  {
    return false;
  }
  const float inv = 1.f / det;
  const Vec3f s = r.origin - tri.v0;
  u = dot(s, p) * inv;
  if (!(u >= 0.f && u <= 1.f))
  {
    return false;
  }
  const Vec3f q = cross(s, tri.e1);
  v = dot(r.direction, q) * inv;
  if (!(v >= 0.f && u + v <= 1.f))
  {
    return false;
  }
  t = dot(tri.e2, q) * inv;
  return t > r.tnear && t < tfar;
}

/// Closest hit (AnyHit = false) or first hit found (AnyHit = true) along `ray`.
/// Returns whether anything was hit; `hit` holds the original triangle index.
template <bool AnyHit>
LINKGI_HOST_DEVICE inline bool traverse(const BvhView& bvh, const Ray& ray, Hit& hit)
{
  hit = Hit{};
  if (bvh.triangleCount == 0)
  {
    return false;
  }
  const PreparedRay r = prepare(ray);
  float tfar = r.tfar;
  int stack[kBvhStackSize];
  int sp = 0;
  int node = bvh.root;
  int hitLeaf = -1;
  float hu = 0.f, hv = 0.f;
  for (;;)
  {
    if (node >= 0)
    {
      const BvhNode n = loadNode(bvh.nodes, node);
      const float t0 = slab(r, tfar, n.lo0x, n.hi0x, n.lo0y, n.hi0y, n.lo0z, n.hi0z);
      const float t1 = slab(r, tfar, n.lo1x, n.hi1x, n.lo1y, n.hi1y, n.lo1z, n.hi1z);
      const bool in0 = t0 <= tfar, in1 = t1 <= tfar;
      if (in0 && in1)
      {
        // Nearer child first, so the closest hit shrinks tfar early.
        const bool swap = t1 < t0;
        node = swap ? n.child[1] : n.child[0];
        if (sp < kBvhStackSize)
        {
          stack[sp++] = swap ? n.child[0] : n.child[1];
        }
        continue;
      }
      if (in0 || in1)
      {
        node = in0 ? n.child[0] : n.child[1];
        continue;
      }
    }
    else
    {
      const int leaf = ~node;
      float t, u, v;
      if (intersectTriangle(r, loadTriangle(bvh.triangles, leaf), tfar, t, u, v))
      {
        tfar = t;
        hitLeaf = leaf;
        hu = u;
        hv = v;
        if (AnyHit)
        {
          break;
        }
      }
    }
    if (sp == 0)
    {
      break;
    }
    node = stack[--sp];
  }
  if (hitLeaf < 0)
  {
    return false;
  }
  hit.triangle = loadTriangle(bvh.triangles, hitLeaf).id;
  hit.u = hu;
  hit.v = hv;
  hit.t = tfar;
  return true;
}
}
}
