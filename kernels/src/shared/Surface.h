// The receiving elements of a mesh (vertex fronts and backs), its triangles' front sides and
// the environment's texels: what every method's gather and direct light agree on.
#pragma once

#include "linkgi/Scene.h"

#include <cstddef>
#include <vector>

namespace linkgi
{
/// Elements are the vertices (front sides) and, for two-sided scenes, their back sides:
/// element vertexCount + i is the back of vertex i (normal -n_i).
struct Elements
{
  std::size_t vertexCount = 0;
  bool twoSided = false;
  LINKGI_HOST_DEVICE std::size_t count() const { return twoSided ? 2 * vertexCount : vertexCount; }
  LINKGI_HOST_DEVICE Index vertexOf(std::size_t e) const { return Index(e < vertexCount ? e : e - vertexCount); }
  LINKGI_HOST_DEVICE float sideSign(std::size_t e) const { return e < vertexCount ? 1.f : -1.f; }
};

/// A triangle's front-side normal (see frontFaceNormals).
LINKGI_HOST_DEVICE inline Vec3f frontFaceNormal(const Vec3f* positions, const Vec3f* normals, const Triangle& t)
{
  const Vec3f& a = positions[t.v[0]];
  const Vec3f n = normalize(cross(positions[t.v[1]] - a, positions[t.v[2]] - a));
  const Vec3f vertexSum = normals[t.v[0]] + normals[t.v[1]] + normals[t.v[2]];
  return dot(n, vertexSum) < 0.f ? -n : n;
}

/// Front-side normal of each triangle: the winding normal, flipped where it disagrees with
/// the sum of its vertex normals (so inconsistent winding does not turn surfaces black).
std::vector<Vec3f> frontFaceNormals(const Scene& scene);

/// Lenv(j): the radiance of each environment texel the matrix Wenv gathers (one entry, the
/// colour, for a constant environment; colour x texel for a lat-long map).
std::vector<Vec3f> environmentTexelRadiance(const Environment& environment);
}
