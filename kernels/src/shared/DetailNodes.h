// Direct light finer than the mesh on its large triangles. A link that hits a triangle
// reads the hit's radiance from the triangle's corners; where a shadow edge or a spot's
// rim crosses a triangle much larger than the scene's detail, the corners do not see it
// (a CAD part of 1,710 points: 14% from the path tracer for this alone). Large triangles
// therefore carry a grid of detail nodes: links that hit them (the link method's, and
// implicit visibility's surface hits) go to the grid's nodes, whose direct light
// is traced on every light change, while everything else they carry (the environment's
// light, bounced light, emission) is interpolated from the corners.
#pragma once

#include "linkgi/Scene.h"
#include "shared/DirectLight.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"

#include <cstdint>
#include <vector>

namespace linkgi
{
/// Where a triangle's nodes are, as linksOfRay reads it (plain data for the GPU). A
/// triangle of `steps` n >= 2 has the grid points (i, j), i + j <= n, at barycentrics
/// (1 - (i + j)/n, i/n, j/n); its corners are its vertices' elements, the others its own
/// nodes, numbered row by row (j, then i) from first[t].
struct DetailGrid
{
  const Index* first = nullptr;         ///< per triangle; null: no triangle is subdivided
  const std::uint16_t* steps = nullptr; ///< per triangle: grid steps per edge, 0 = not subdivided
  Index columnBase = 0;                 ///< the nodes' first column: the element count
  Index nodesPerSide = 0;               ///< back-side nodes follow the front sides' (two-sided)
};

/// The column of grid point (i, j) of triangle t (n steps) on the front or back side.
LINKGI_HOST_DEVICE inline Index detailColumn(const DetailGrid& g, Index t, const Triangle& tri, int n,
  int i, int j, bool back, Index vertexCount)
{
  const Index side = back ? vertexCount : 0;
  if (j == 0 && (i == 0 || i == n))
  {
    return tri.v[i == 0 ? 0 : 1] + side;
  }
  if (i == 0 && j == n)
  {
    return tri.v[2] + side;
  }
  const int row = j * (n + 1) - j * (j - 1) / 2 + i; // among all grid points
  const int local = row - 1 - (row > n ? 1 : 0);     // less the corners before it
  return g.columnBase + (back ? g.nodesPerSide : 0) + g.first[t] + Index(local);
}

/// The grid points around barycentrics (1 - u - v, u, v) of a subdivided triangle and their
/// weights: the corners of the grid's cell that holds the point, linearly.
LINKGI_HOST_DEVICE inline void detailCell(const DetailGrid& g, Index t, const Triangle& tri, float u,
  float v, bool back, Index vertexCount, Index column[3], float weight[3])
{
  const int n = g.steps[t];
  const float x = fminf(fmaxf(u, 0.f), 1.f) * float(n), y = fminf(fmaxf(v, 0.f), 1.f) * float(n);
  int i = int(x), j = int(y);
  i = i > n - 1 ? n - 1 : i;
  j = j > n - 1 - i ? n - 1 - i : j;
  const float fx = x - float(i), fy = y - float(j);
  if (fx + fy <= 1.f)
  {
    column[0] = detailColumn(g, t, tri, n, i, j, back, vertexCount);
    column[1] = detailColumn(g, t, tri, n, i + 1, j, back, vertexCount);
    column[2] = detailColumn(g, t, tri, n, i, j + 1, back, vertexCount);
    weight[0] = 1.f - fx - fy;
    weight[1] = fx;
    weight[2] = fy;
  }
  else
  {
    column[0] = detailColumn(g, t, tri, n, i + 1, j + 1, back, vertexCount);
    column[1] = detailColumn(g, t, tri, n, i, j + 1, back, vertexCount);
    column[2] = detailColumn(g, t, tri, n, i + 1, j, back, vertexCount);
    weight[0] = fx + fy - 1.f;
    weight[1] = 1.f - fx;
    weight[2] = 1.f - fy;
  }
}

/// The grid point nearest barycentrics (1 - u - v, u, v) of a subdivided triangle: of its
/// grid cell's corners (detailCell), the one of the largest weight.
LINKGI_HOST_DEVICE inline Index detailNearestColumn(const DetailGrid& g, Index t, const Triangle& tri, float u,
  float v, bool back, Index vertexCount)
{
  Index column[3];
  float weight[3];
  detailCell(g, t, tri, u, v, back, vertexCount, column, weight);
  const int k = weight[0] >= weight[1] && weight[0] >= weight[2] ? 0 : weight[1] >= weight[2] ? 1 : 2;
  return column[k];
}

/// One node of a subdivided triangle: the triangle and the node's barycentrics there.
struct DetailNode
{
  Index triangle = 0;
  float u = 0.f, v = 0.f;
};

/// A node's outgoing radiance on side `side` (0 front, 1 back): its corners' radiance less
/// their own direct light's share (rho/pi E_d), interpolated, and the share of its own E_d
/// (`nodeDirect`) with the corners' albedo interpolated. `radiance(e)` reads element e's,
/// `direct` is E_d per element, `albedo` per vertex.
template <typename RadianceAt>
LINKGI_HOST_DEVICE inline Vec3f detailNodeRadiance(const DetailNode& node, const Triangle& tri, int side,
  Index vertexCount, const RadianceAt& radiance, const Vec3f* direct, const Vec3f* albedo,
  const Vec3f& nodeDirect)
{
  const float c[3] = { 1.f - node.u - node.v, node.u, node.v };
  Vec3f sum(0.f), rho(0.f);
  for (int k = 0; k < 3; ++k)
  {
    const Index e = tri.v[k] + (side ? vertexCount : 0);
    const Vec3f& a = albedo[tri.v[k]];
    sum += (radiance(e) - a * direct[e] * (1.f / kPi)) * c[k];
    rho += a * c[k];
  }
  return sum + rho * nodeDirect * (1.f / kPi);
}

/// E_d at a node on side `side`: from lights[0, count), one shadow ray each from
/// the node lifted off its triangle as the corners' rays are (triangleOffset) and shifted
/// towards the triangle's centroid; the normal interpolated from the corners' (the face's
/// where the corners' cancel).
template <typename Occluded>
LINKGI_HOST_DEVICE inline Vec3f detailNodeDirect(const DetailNode& node, int side, const Triangle* triangles,
  const Vec3f* positions, const Vec3f* normals, const Vec3f* faceNormals, const RayOrigin* origins,
  const Light* lights, Index count, const Occluded& occluded)
{
  const Triangle tri = triangles[node.triangle];
  const float c[3] = { 1.f - node.u - node.v, node.u, node.v };
  Vec3f p(0.f), n(0.f);
  for (int k = 0; k < 3; ++k)
  {
    p += positions[tri.v[k]] * c[k];
    n += normals[tri.v[k]] * c[k];
  }
  n = dot(n, n) > 1e-12f ? normalize(n) : faceNormals[node.triangle];
  n = side ? -n : n;
  // Shifted 1% of the way to the centroid as vertices' origins are to their one-ring's: a
  // node on an edge in a concave crease lies in the other face's plane.
  const Vec3f centroid = (positions[tri.v[0]] + positions[tri.v[1]] + positions[tri.v[2]]) * (1.f / 3.f);
  const Vec3f origin = p + n * triangleOffset(origins, tri) + (centroid - p) * 0.01f;
  return shadowedIrradiance(lights, count, p, n, origin, occluded);
}

/// A mesh's subdivided triangles and their nodes (front sides; the back sides, when
/// two-sided, are the same nodes after them).
struct DetailNodes
{
  std::vector<Index> first;         ///< per triangle (empty: none subdivided)
  std::vector<std::uint16_t> steps; ///< per triangle
  std::vector<DetailNode> nodes;
  float spacing = 0.f;              ///< the grid's step: no cell edge is longer

  bool empty() const { return nodes.empty(); }
  /// Node columns per element count (the column space is elements, then nodes per side).
  DetailGrid grid(std::size_t elementCount) const { return grid(elementCount, first.data(), steps.data()); }
  /// The same over copies of `first` and `steps` elsewhere (a GPU's).
  DetailGrid grid(std::size_t elementCount, const Index* firstCopy, const std::uint16_t* stepsCopy) const;
  /// Columns beyond the elements: the nodes, once per side.
  std::size_t columns(bool twoSided) const { return nodes.size() * (twoSided ? 2 : 1); }
};

/// The node budget of a mesh of `vertices` vertices: as many as its vertices, at least 4,096.
std::size_t detailNodeBudget(std::size_t vertices);

/// The most nodes detailNodes gives a mesh of this size: its budget, and no more than the
/// largest grid on each triangle that may get one (at most half of them: those twice the
/// median's size or larger).
std::size_t detailNodeBound(std::size_t vertices, std::size_t triangles);

/// Grids on the triangles larger than the mesh's own detail: those whose longest edge is at
/// least twice the median triangle's and twice 1/256 of the mesh's diagonal (a mesh of even
/// triangles gets none, however coarse). Their steps are of one spacing for the whole mesh,
/// the finest whose nodes fit `budget` but no finer than 1/256 of the diagonal; a triangle
/// that spans fewer than two steps of it gets none.
DetailNodes detailNodes(const Scene& scene, std::size_t budget);

/// detailNodeDirect at every node, fronts then backs when two-sided.
std::vector<Vec3f> detailNodeDirect(const Scene& scene, const DetailNodes& detail,
  const std::vector<RayOrigin>& origins, const std::vector<Vec3f>& faceNormals,
  const RayTracer& tracer, bool twoSided, std::uint64_t* shadowRays = nullptr);

/// radiance[columnBase + k] = detailNodeRadiance of node column k (fronts, then backs when
/// two-sided), from the elements' radiance (radiance[0, elements)), their E_d `direct` and
/// the nodes' E_d `nodeDirect` (detailNodeDirect's).
void detailNodeRadiance(const Scene& scene, const DetailNodes& detail, bool twoSided, const Vec3f* direct,
  const Vec3f* nodeDirect, std::size_t columnBase, Vec3f* radiance);

}
