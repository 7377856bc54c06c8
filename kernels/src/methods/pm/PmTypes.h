// Photon mapping's plain-data layout, for the CPU backend and the CUDA backend alike: the
// kd-tree of PointTree as raw arrays (the implicit median tree: node i of a range is
// order[mid], split on axes[mid]), and the searches on it: the nearest point, the k nearest,
// every point within a radius. Host and device code include this header; the CPU builds the
// arrays with PointTree, the GPU with pm/PmKernels.h's DevicePointTree, and both search them
// with these functions. What the searches find does not depend on the tree's shape.
#pragma once

#include "linkgi/Config.h"
#include "linkgi/Math.h"

#include <cstdint>

namespace linkgi::pm
{
/// Ranges of at most this many points are leaves (PointTree::build stops there).
constexpr std::uint32_t kTreeLeaf = 8;
/// A gather hit reads the nearest estimate whose normal is within 37 degrees of its own, the
/// cone of the photons the estimate averages (kEstimateCos, PmMath.h): an estimate speaks
/// for the surface that faces its way; at 60 degrees, hits on the dark flank of a thin part
/// (a spider's leg) read the estimates of its lit top...
constexpr float kLookupCos = 0.8f;
/// ...and that lies within 30 degrees of its tangent plane (sin 30 = 0.5): an estimate on
/// another surface that faces the same way, across a thin wall or a fold (the bright inside
/// of a double-walled lamp shade behind its outside), lies off that plane. On a curved
/// surface the nearest estimates at a distance d lie about d / 2R below it.
constexpr float kLookupPlaneSin = 0.5f;
/// Depth of the explicit stack: a median tree of 2^32 points with leaves of 8 is 30 deep.
constexpr int kTreeStack = 64;

/// PointTree's arrays, borrowed: points[order[i]] is the point at tree position i. Without
/// `order` the points are stored in tree order (a GPU copies them so, for its caches).
struct PointTreeView
{
  const Vec3f* points = nullptr;
  const Index* order = nullptr;
  const std::uint8_t* axes = nullptr; ///< split axis of the node whose median is at tree position i
  std::uint32_t count = 0;
  LINKGI_HOST_DEVICE Index at(std::uint32_t i) const { return order ? order[i] : i; }
};

/// A found point: its squared distance and index. Searches order them by (d2, index).
struct Neighbour
{
  float d2;
  Index index;
};

LINKGI_HOST_DEVICE inline bool nearer(const Neighbour& a, const Neighbour& b)
{
  return a.d2 < b.d2 || (a.d2 == b.d2 && a.index < b.index);
}

/// The traversal every search shares: visits the points of the tree that can be within the
/// current bound (`bound()`, a squared distance, re-read as it shrinks) of q, nearer side
/// first; `visit(index, d2)` is called for each point within it.
template <typename Bound, typename Visit>
LINKGI_HOST_DEVICE inline void visitNear(const PointTreeView& t, const Vec3f& q, Bound&& bound, Visit&& visit)
{
  const auto consider = [&](Index i) {
    const Vec3f d = t.points[i] - q;
    const float d2 = dot(d, d);
    if (d2 <= bound())
    {
      visit(i, d2);
    }
  };
  // Each entry: a range, and the squared distance to the splitting plane that must not
  // exceed the bound for the range to be searched (0 for ranges searched unconditionally).
  std::uint32_t begin[kTreeStack], end[kTreeStack];
  float plane[kTreeStack];
  int top = 0;
  begin[0] = 0;
  end[0] = t.count;
  plane[0] = 0.f;
  while (top >= 0)
  {
    const std::uint32_t b = begin[top], e = end[top];
    const float p = plane[top];
    --top;
    if (p > bound() || b >= e)
    {
      continue;
    }
    if (e - b <= kTreeLeaf)
    {
      for (std::uint32_t i = b; i < e; ++i)
      {
        consider(t.at(i));
      }
      continue;
    }
    const std::uint32_t mid = (b + e) / 2;
    const Index m = t.at(mid);
    const int axis = t.axes[mid];
    const float diff = q[axis] - t.points[m][axis];
    consider(m);
    const bool leftFirst = diff < 0.f;
    // The far side first onto the stack, so the near side is searched first.
    ++top;
    begin[top] = leftFirst ? mid + 1 : b;
    end[top] = leftFirst ? e : mid;
    plane[top] = diff * diff;
    ++top;
    begin[top] = leftFirst ? b : mid + 1;
    end[top] = leftFirst ? mid : e;
    plane[top] = 0.f;
  }
}

/// The k nearest points to q within sqrt(maxDistance2) for which accept(index) holds (by
/// (d2, index), so ties go to the smaller index) into `heap` (room for k), as a max-heap:
/// heap[0] is the farthest found. Returns how many (at most k).
template <typename Accept>
LINKGI_HOST_DEVICE inline std::uint32_t kNearest(const PointTreeView& t, const Vec3f& q, std::uint32_t k,
  float maxDistance2, Accept&& accept, Neighbour* heap)
{
  std::uint32_t size = 0;
  if (k == 0)
  {
    return 0;
  }
  const auto bound = [&]() { return size == k ? heap[0].d2 : maxDistance2; };
  visitNear(t, q, bound, [&](Index i, float d2) {
    const Neighbour n{ d2, i };
    if ((size == k && !nearer(n, heap[0])) || !accept(i))
    {
      return;
    }
    std::uint32_t at;
    if (size < k)
    {
      at = size++; // sift up from the end
      while (at > 0 && nearer(heap[(at - 1) / 2], n))
      {
        heap[at] = heap[(at - 1) / 2];
        at = (at - 1) / 2;
      }
    }
    else
    {
      at = 0; // replace the farthest, sift down
      for (;;)
      {
        std::uint32_t c = 2 * at + 1;
        if (c >= size)
        {
          break;
        }
        if (c + 1 < size && nearer(heap[c], heap[c + 1]))
        {
          ++c;
        }
        if (!nearer(n, heap[c]))
        {
          break;
        }
        heap[at] = heap[c];
        at = c;
      }
    }
    heap[at] = n;
  });
  return size;
}

/// visit(index, d2) for every point within sqrt(maxDistance2) of q, in no particular order.
template <typename Visit>
LINKGI_HOST_DEVICE inline void forEachWithin(const PointTreeView& t, const Vec3f& q, float maxDistance2, Visit&& visit)
{
  visitNear(t, q, [maxDistance2]() { return maxDistance2; }, visit);
}

/// The nearest point to q for which accept(index) holds (ties to the smaller index), or
/// kInvalidIndex; no recursion and no heap, so it runs in a CUDA thread.
template <typename Accept>
LINKGI_HOST_DEVICE inline Index nearestOne(const PointTreeView& t, const Vec3f& q, float maxDistance2, Accept&& accept)
{
  Index best = kInvalidIndex;
  float bound = maxDistance2;
  visitNear(t, q, [&bound]() { return bound; }, [&](Index i, float d2) {
    if ((d2 < bound || best == kInvalidIndex || i < best) && accept(i))
    {
      bound = d2;
      best = i;
    }
  });
  return best;
}

/// The radiance estimates of the global photon map, borrowed (PhotonMap's site arrays).
struct RadianceSitesView
{
  PointTreeView tree; ///< over the site positions
  const Vec3f* normals = nullptr;
  const Vec3f* radiance = nullptr;
  /// Per estimate: the squared radius of the disc its photons were gathered from, the only
  /// points it speaks for.
  const float* radius2 = nullptr;
  float maxDistance2 = 3.4e38f; ///< a hit with no estimate this near sees none
};

/// The estimate a gather ray reads at surface point y (unit normal n): the nearest within
/// sqrt(maxDistance2) that faces within 37 degrees of n and lies within 30 degrees of y's
/// tangent plane, where its photons' disc holds y; kInvalidIndex otherwise. An estimate is an
/// average over its disc: read further out, where its photons say nothing, it lit the floor
/// under an object resting on it, which no photon reaches, with the light of the floor around
/// the object. (Where photons lie about y, the nearest estimate's disc holds it: every
/// siteStride-th photon has one, and each disc holds estimatePhotons of them.)
LINKGI_HOST_DEVICE inline Index estimateAt(const RadianceSitesView& s, const Vec3f& y, const Vec3f& n)
{
  if (s.tree.count == 0)
  {
    return kInvalidIndex;
  }
  const Index i = nearestOne(s.tree, y, s.maxDistance2, [&](Index j) {
    const Vec3f d = s.tree.points[j] - y;
    const float h = dot(d, n);
    return dot(s.normals[j], n) > kLookupCos && h * h <= kLookupPlaneSin * kLookupPlaneSin * dot(d, d);
  });
  if (i == kInvalidIndex)
  {
    return kInvalidIndex;
  }
  const Vec3f d = s.tree.points[i] - y;
  return dot(d, d) <= s.radius2[i] ? i : kInvalidIndex;
}

/// The outgoing radiance of estimateAt(s, y, n), zero where there is none.
LINKGI_HOST_DEVICE inline Vec3f lookupRadiance(const RadianceSitesView& s, const Vec3f& y, const Vec3f& n)
{
  const Index i = estimateAt(s, y, n);
  return i == kInvalidIndex ? Vec3f(0.f) : s.radiance[i];
}
}
