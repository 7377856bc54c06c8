// The implicit-visibility method's per-item formulas, host and device code: one step of the
// pair recursion that creates the node links, and the geometry of pushing a link to a leaf
// (the discs drawn into several bins). The CPU backend (ImplicitLinks.cpp, PushToLeaves.cpp)
// and the CUDA backend (IvKernels.cu) both call them.
#pragma once

#include "linkgi/Math.h"
#include "linkgi/Scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace linkgi::iv
{
/// Clusters whose normals agree within this (radians) are flat: one normal for all.
constexpr float kFlatCone = 1e-3f;

/// What the pair recursion reads of a node, in one 48-byte record: each visited pair reads
/// two nodes at random, and the tree's separate arrays cost six cache lines per node.
struct NodeBounds
{
  Vec3f position;
  float radius;
  Vec3f normal;
  float planeDeviation;
  float coneAngle, coneSin, coneCos;
  Index firstChild; ///< left child, kInvalidIndex for a leaf
};

/// How far a node's surface reaches from its position, and the slab about its plane that
/// holds it: a cluster's bounding sphere and slab, a leaf's element (ClusterTree::extent,
/// extentSlab), which reaches beyond its disc.
struct Reach
{
  float radius, slab;
};

/// Whether some disc point of `a` can see some point of `b` in front of it (a can receive
/// from b); conservative, from the nodes' bounds and b's `reach`. d = p_b - p_a, r2 = |d|^2.
LINKGI_HOST_DEVICE inline bool canReceive(const NodeBounds& a, const NodeBounds& b, const Reach& reachB,
  const Vec3f& d, float r2, float eps)
{
  if (a.coneAngle < kFlatCone)
  {
    // Every receiving normal is n_a: q in b is in front of p in a when n_a.(q - p) > 0,
    // i.e. n_a.d + rise + deviation_a > eps, where rise in [0, radius_b] is how far b's
    // points rise above the plane through b's centre with a's normal. Most pairs are
    // decided by the bounds of rise, without its square root.
    const float front = dot(a.normal, d) + a.planeDeviation - eps;
    if (front > 0.f || front + reachB.radius <= 0.f)
    {
      return front > 0.f;
    }
    const float along = std::abs(dot(a.normal, b.normal));
    const float across = std::sqrt(std::max(0.f, 1.f - along * along));
    return front + std::min(reachB.radius, along * reachB.slab + across * reachB.radius) > 0.f;
  }
  const float reach = a.radius + reachB.radius;
  if (r2 <= reach * reach || a.coneCos <= 0.f)
  {
    return true;
  }
  // Some direction between the two lies within cone + asin(reach / r) of n_a's horizon:
  // cos(n_a, d) > -sin(cone + asin(reach / r)).
  const float r = std::sqrt(r2);
  const float sinB = reach / r, cosB = std::sqrt(1.f - sinB * sinB);
  const float cosSpread = a.coneCos * cosB - a.coneSin * sinB;
  return cosSpread <= 0.f || dot(a.normal, d) > -r * (a.coneSin * cosB + a.coneCos * sinB);
}

/// The pair recursion's rules over a tree (ClusterTree's numbering: leaves first, interior
/// node leafCount + i has children left[i], right[i]).
struct PairRules
{
  const NodeBounds* nodes = nullptr;
  const Index* left = nullptr;
  const Index* right = nullptr;
  Index leafCount = 0;
  float binSolidAngle = 0.f; ///< the subdivision threshold (CubeBins::meanSolidAngle)
  float planeEpsilon = 0.f;
  float maxConeAngle = 0.f;
  /// Per node, or null for all: whether a leaf below it is this process's (a partition's
  /// row). Links are then made only into such nodes, and a pair of which neither is one is
  /// not followed: what the process pushes to its leaves is unchanged.
  const std::uint8_t* ownBelow = nullptr;
  /// Per leaf, or null: how far its element reaches and the slab it lies in
  /// (ClusterTree::extent, extentSlab), for canReceive.
  const float* extents = nullptr;
  const float* extentSlabs = nullptr;

  /// One step of the recursion over the pair (a, b): links it (emit(receiver, source), for
  /// each end that can receive), prunes it, or pushes the pairs of a subdivision.
  template <typename Emit, typename Push>
  LINKGI_HOST_DEVICE void visit(Index a, Index b, Emit& emit, Push& push) const
  {
    if (ownBelow && !ownBelow[a] && !ownBelow[b])
    {
      return;
    }
    const NodeBounds& na = nodes[a];
    if (a == b)
    {
      if (na.firstChild != kInvalidIndex)
      {
        const Index i = a - leafCount;
        push(left[i], left[i]);
        push(right[i], right[i]);
        push(left[i], right[i]);
      }
      return;
    }
    const NodeBounds& nb = nodes[b];
    const Vec3f d = nb.position - na.position;
    const float r2 = dot(d, d);
    const bool aReceives = canReceive(na, nb, reach(b), d, r2, planeEpsilon);
    const bool bReceives = canReceive(nb, na, reach(a), -d, r2, planeEpsilon);
    if (!aReceives && !bReceives)
    {
      return;
    }
    // pi R^2 / r^2 > bin solid angle: the node covers more than a bin from the other end.
    const float limit = binSolidAngle * r2 * (1.f / kPi);
    const bool bigA = tooBig(na, limit), bigB = tooBig(nb, limit);
    if (bigA || bigB)
    {
      const Index split = bigA && (!bigB || na.radius >= nb.radius) ? a : b;
      const Index other = split == a ? b : a;
      const Index i = split - leafCount;
      push(left[i], other);
      push(right[i], other);
      return;
    }
    if (aReceives && (!ownBelow || ownBelow[a]))
    {
      emit(a, b);
    }
    if (bReceives && (!ownBelow || ownBelow[b]))
    {
      emit(b, a);
    }
  }

  LINKGI_HOST_DEVICE Reach reach(Index x) const
  {
    return extents && x < leafCount ? Reach{ extents[x], extentSlabs[x] }
                                    : Reach{ nodes[x].radius, nodes[x].planeDeviation };
  }

  LINKGI_HOST_DEVICE bool tooBig(const NodeBounds& x, float limit) const
  {
    return x.firstChild != kInvalidIndex && (x.radius * x.radius > limit || x.coneAngle > maxConeAngle);
  }
};

/// A leaf disc wider than a bin as seen from the receiver (it cannot be subdivided), at a
/// distance r of more than twice its radius: offers points on rings of the disc, spaced a
/// bin apart as seen from the receiver, so that every bin it covers holds it.
template <typename Offer>
LINKGI_HOST_DEVICE void splatDisc(const Vec3f& center, const Vec3f& normal, float radius, float r,
  float binAngle, Offer& offer)
{
  const Frame f = Frame::fromNormal(normal);
  const float step = binAngle * r;
  const int rings = std::min(8, int(std::ceil(radius / step)));
  for (int i = 1; i <= rings; ++i)
  {
    const float ringRadius = radius * float(i) / float(rings);
    const int points = std::min(64, std::max(6, int(std::ceil(2.f * kPi * ringRadius / step))));
    // The ring's points by rotating one step at a time (one sincos per ring, not per point).
    const float stepAngle = 2.f * kPi / float(points), phase = 0.5f * float(i % 2) * stepAngle;
    const float cosStep = std::cos(stepAngle), sinStep = std::sin(stepAngle);
    float c = std::cos(phase) * ringRadius, s = std::sin(phase) * ringRadius;
    for (int k = 0; k < points; ++k)
    {
      offer(center + f.toWorld(Vec3f(c, s, 0.f)));
      const float next = c * cosStep - s * sinStep;
      s = s * cosStep + c * sinStep;
      c = next;
    }
  }
}

/// How a source leaf at squared distance r2 from the receiver enters its bins: as its
/// centre alone (narrower than a bin), splatted as a disc (wider than a bin, showing the
/// receiver its front), or drawn from its own surface (closer than twice its radius, or
/// wider than a bin and showing the receiver its back).
enum class LeafReach
{
  Centre,
  Splat,
  Surface
};

/// `facing` = n_disc . (receiver - centre). A disc is its vertex's tangent plane; the
/// surface bends away from it by about curvature x radius^2, so where a leaf is near
/// (within twice its `extent`, ClusterTree::extent: the element of a long thin triangle's
/// corner reaches far beyond its disc's radius) its disc misplaces the surface by as much
/// as the distance itself: at a crease the disc of a split twin at the same position covers up to the
/// whole hemisphere from in front or from behind, whichever way the surface really turns;
/// over a convex edge a rim reaches past the neighbouring faces. Such a leaf is drawn from
/// its surface (surfaceHit). So is one seen from behind that spans several bins: its back
/// hides what lies beyond it (a surface enclosing the receiver hides the sky), where the
/// centre alone would let it through and its disc would blacken bins its surface does not
/// reach. A leaf narrower than a bin fills it whole (the paper's Eq. 5), whichever side
/// it shows.
LINKGI_HOST_DEVICE inline LeafReach leafReach(float radius, float extent, float r2, float binAngle, float facing)
{
  const bool wide = radius * radius > 0.25f * binAngle * binAngle * r2;
  return 4.f * extent * extent > r2 || (wide && !(facing > 0.f)) ? LeafReach::Surface
    : wide                                                       ? LeafReach::Splat
                                                                 : LeafReach::Centre;
}

/// Whether a node's link to `source` (d = its position - the node's, d2 = |d|^2) stays
/// whatever its bin's shortest is: a leaf the push draws from its surface covers bins
/// beside its centre's, so a nearer link in its centre's bin hides only part of it (a
/// split twin at a box's edge shares its bin and distance with the other face's vertex).
LINKGI_HOST_DEVICE inline bool keptWhole(bool sourceIsLeaf, float radius, float extent, const Vec3f& normal,
  const Vec3f& d, float d2, float binAngle)
{
  return sourceIsLeaf && leafReach(radius, extent, d2, binAngle, -dot(normal, d)) == LeafReach::Surface;
}

/// A bin's source drawn from its surface (surfaceHit) carries this bit, and its back the
/// next: such a source is the side of the surface hit, not the side its disc faces.
constexpr Index kSurfaceHit = Index(1) << 31;
constexpr Index kSurfaceBack = Index(1) << 30;
constexpr Index kSourceMask = kSurfaceBack - 1;

/// Where the ray o + t dir meets the element of the vertex at `corner` of triangle
/// (p0, p1, p2): the part of the triangle where that vertex's barycentric coordinate is
/// the largest (a third of its area; over its adjacent triangles, the vertex's area as
/// vertexAreas counts it). Returns t > 0, or a negative value when it misses; `back` tells
/// whether the ray meets the triangle's back: the side its `front` normal (frontFaceNormals:
/// the side the vertex normals point to, whatever the winding) points away from; `hitU`,
/// `hitV` the hit's barycentrics (1 - u - v, u, v) on the triangle.
LINKGI_HOST_DEVICE inline float surfaceHit(const Vec3f& o, const Vec3f& dir, const Vec3f& p0, const Vec3f& p1,
  const Vec3f& p2, int corner, const Vec3f& front, bool& back, float& hitU, float& hitV)
{
  const Vec3f e1 = p1 - p0, e2 = p2 - p0;
  const Vec3f pv = cross(dir, e2);
  const float det = dot(e1, pv);
  if (det == 0.f)
  {
    return -1.f;
  }
  const float inv = 1.f / det;
  const Vec3f tv = o - p0;
  const float u = dot(tv, pv) * inv;
  const Vec3f qv = cross(tv, e1);
  const float v = dot(dir, qv) * inv;
  const float w = 1.f - u - v;
  if (!(u >= 0.f && v >= 0.f && w >= 0.f))
  {
    return -1.f;
  }
  const float mine = corner == 0 ? w : corner == 1 ? u : v;
  if (mine < w || mine < u || mine < v)
  {
    return -1.f;
  }
  back = dot(dir, front) > 0.f;
  hitU = u;
  hitV = v;
  const float t = dot(e2, qv) * inv;
  return t > 0.f ? t : -1.f;
}

/// A bin's candidate as one ordered key: the shorter distance wins, then the smaller
/// source (distances are positive, so their bits order as the values do).
LINKGI_HOST_DEVICE inline std::uint64_t binKey(float d2, Index source)
{
#ifdef __CUDA_ARCH__
  const std::uint32_t bits = __float_as_uint(d2);
#else
  std::uint32_t bits;
  std::memcpy(&bits, &d2, sizeof bits);
#endif
  return (std::uint64_t(bits) << 32) | source;
}
constexpr std::uint64_t kEmptyBin = ~std::uint64_t(0);
}
