// Where a vertex's rays start: a little off its surface along the normal, and shifted into
// its one-ring. One record per vertex, read by every method on the CPU and the GPU.
#pragma once

#include "linkgi/Scene.h"
#include "scene/Topology.h"

#include <vector>

namespace linkgi
{
/// A vertex's ray origin relative to the vertex (see rayOrigins).
struct RayOrigin
{
  Vec3f shift;        ///< in the tangent plane, towards the one-ring's centroid
  float offset = 0.f; ///< along the normal, to the side the rays leave from
};

/// The smallest offset of ray origins relative to the largest coordinate of the point: 16
/// times single precision's rounding there (2^-24 relative). The origin itself is rounded
/// once, and a ray-triangle test on the triangles around it errs by a few roundings, so a
/// ray never hits the surface it leaves.
constexpr float kOffsetPrecision = 9.536743e-7f; // 2^-20

/// The shift of a vertex's ray origins: 1% of the way to the centroid of its one-ring
/// `ring[0, ringSize)`, in its tangent plane. A vertex in a concave corner (a floor meeting
/// a wall) lies exactly in the other surface's plane, so half its rays would otherwise start
/// on that plane and leak through it.
LINKGI_HOST_DEVICE inline Vec3f originShift(const Vec3f* positions, const Vec3f& position,
  const Vec3f& normal, const Index* ring, Index ringSize)
{
  constexpr float kShift = 0.01f;
  if (ringSize == 0)
  {
    return Vec3f(0.f);
  }
  Vec3f centroid(0.f);
  for (Index i = 0; i < ringSize; ++i)
  {
    centroid += positions[ring[i]];
  }
  centroid = centroid / float(ringSize);
  Vec3f toCentroid = centroid - position;
  toCentroid -= normal * dot(normal, toCentroid); // stay in the tangent plane
  return toCentroid * kShift;
}

/// The offset of a vertex's ray origins along its normal: 1% of its shortest edge, so that a
/// millimetre detail in a hundred-metre scene starts its rays inside its own millimetres, at
/// least kOffsetPrecision of its largest coordinate, and at most `bound` (rayEpsilon: the
/// offset that suits coarse meshes, where 1% of an edge would be far more).
LINKGI_HOST_DEVICE inline float originOffset(const Vec3f* positions, const Vec3f& position,
  const Index* ring, Index ringSize, float bound)
{
  float shortest = bound * 100.f;
  for (Index i = 0; i < ringSize; ++i)
  {
    const float length = std::sqrt(dot(positions[ring[i]] - position, positions[ring[i]] - position));
    shortest = length > 0.f ? fminf(shortest, length) : shortest;
  }
  const float precision = kOffsetPrecision *
    fmaxf(fabsf(position.x), fmaxf(fabsf(position.y), fabsf(position.z)));
  return fminf(bound, fmaxf(0.01f * shortest, precision));
}

LINKGI_HOST_DEVICE inline RayOrigin rayOrigin(const Vec3f* positions, const Vec3f& position,
  const Vec3f& normal, const Index* ring, Index ringSize, float bound)
{
  return { originShift(positions, position, normal, ring, ringSize),
    originOffset(positions, position, ring, ringSize, bound) };
}

/// The offset for rays leaving a point of triangle `t` (a light path's or a gather ray's
/// hit): the smallest of its vertices'.
LINKGI_HOST_DEVICE inline float triangleOffset(const RayOrigin* origins, const Triangle& t)
{
  return fminf(origins[t.v[0]].offset, fminf(origins[t.v[1]].offset, origins[t.v[2]].offset));
}

/// Where element rays start: off the surface along the side's normal, and shifted towards
/// the one-ring centroid.
LINKGI_HOST_DEVICE inline Vec3f elementRayOrigin(const Vec3f& position, const Vec3f& sideNormal,
  const RayOrigin& origin)
{
  return position + sideNormal * origin.offset + origin.shift;
}

/// Shadow-ray origin of vertex v's sample on side `sign` (+1 front, -1 back).
LINKGI_HOST_DEVICE inline Vec3f vertexLightOrigin(const Vec3f& p, const Vec3f& n, const RayOrigin& origin,
  float sign)
{
  return p + n * (sign * origin.offset) + origin.shift;
}

/// Shadow-ray origin of the midpoint sample of edge (a, b): offset along the mean normal
/// (a's normal where the two cancel) by the smaller offset, and by the mean shift.
LINKGI_HOST_DEVICE inline Vec3f edgeLightOrigin(const Vec3f& pa, const Vec3f& pb, const Vec3f& na,
  const Vec3f& nb, const RayOrigin& a, const RayOrigin& b, float sign)
{
  Vec3f n = normalize(na + nb);
  if (dot(n, n) == 0.f)
  {
    n = na;
  }
  return (pa + pb) * 0.5f + n * (sign * fminf(a.offset, b.offset)) + (a.shift + b.shift) * 0.5f;
}

/// The largest ray offset: 1e-4 of the scene's bounding diagonal.
float rayEpsilon(const Scene& scene);
/// rayEpsilon of a scene whose bounding diagonal is known.
inline float rayEpsilon(float diagonal)
{
  return 1e-4f * diagonal;
}

/// Every vertex's ray origin from its one-ring (rayOrigin with rayEpsilon as the bound).
std::vector<RayOrigin> rayOrigins(const Scene& scene, const Topology& topology);

/// What light paths and proxies read from the positions alone: their box, boundingDiagonal
/// and rayEpsilon (the bound of the ray origins' offsets). A backend that keeps it from its
/// geometry stage spares a light move the passes over the positions.
struct SceneExtent
{
  Vec3f lo{ 0.f }, hi{ 0.f };
  float diagonal = 0.f, eps = 0.f;
};
SceneExtent sceneExtent(const Scene& scene);
}
