// Link generation and compression: the vertex-to-vertex transport matrix W.
#pragma once

#include "cpu/Parallel.h"
#include "linkgi/Scene.h"
#include "shared/DetailNodes.h"
#include "scene/Topology.h"
#include "shared/Csr.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "shared/Surface.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace linkgi
{
/// Upper bound of the compressed links one element keeps in W and Wenv: every ray gives at
/// most 3 (a hit, spread over its triangle's vertices) or 1 (a miss, one texel), and a row
/// has no more columns than there are elements or texels. The compression reserves this much
/// (address space until written); the memory budget's estimate assumes it.
struct LinksPerElement
{
  std::uint64_t transport = 0, environment = 0;
  static LinksPerElement bound(std::uint64_t raysPerVertex, std::uint64_t elements, std::uint64_t texels)
  {
    return { std::min(3 * raysPerVertex, elements), std::min(raysPerVertex, texels) };
  }
};

/// What link generation produces. With cosine-weighted directions the geometry term and the
/// pdf cancel: E_ind(x) = sum_y W[x][y] L(y) + sum_j Wenv[x][j] Lenv(j), each hit adding
/// pi/n_C * barycentric weight to the links towards the hit triangle's three vertices, each
/// miss pi/n_C to the environment texel it sees (one texel when the environment is a
/// constant colour).
struct LinkStructure
{
  SparseMatrix transport;   ///< W: element -> element
  SparseMatrix environment; ///< Wenv: element -> environment texel
  std::uint64_t rays = 0;
  std::uint64_t rawLinks = 0; ///< links before merging equal (x, y) pairs, misses included
};

struct LinkOptions
{
  std::uint32_t raysPerVertex = 256;
  bool twoSided = false;
  bool twist = true;
  std::uint32_t seed = 0;
  /// Per element, or null for all: only rows marked 1 are linked (Partition), the others
  /// stay empty.
  const std::uint8_t* rows = nullptr;
  /// The mesh's detail nodes (null or empty: hits link to their triangle's corners only).
  const DetailNodes* detail = nullptr;
};

/// Per ray: the triangle hit (kInvalidIndex = miss) and its barycentrics.
struct LinkHits
{
  std::vector<Hit> hits; ///< elements x raysPerVertex, row-major
  std::uint32_t raysPerVertex = 0;
};

/// What turning one ray's hit into links needs besides the hit: plain data for the GPU.
struct LinkParams
{
  Index vertexCount = 0;
  bool twoSided = false;
  float weight = 0.f;  ///< pi / n_C
  int envWidth = 0;    ///< lat-long environment size, 0 x 0 for a constant colour (texel 0)
  int envHeight = 0;
  DetailGrid detail;   ///< hits on subdivided triangles link to their nodes
};

/// The links one ray adds to its element's row: up to three (element, weight) pairs for a
/// hit (barycentric weights, back sides offset by vertexCount; on a subdivided triangle the
/// detail nodes around the hit), one environment texel for a miss, none for a back-face hit
/// on one-sided elements (the ray is blocked and sees black).
struct RayLinks
{
  Index column[3];
  float weight[3];
  int count = 0;
  bool environment = false;
};

LINKGI_HOST_DEVICE inline RayLinks linksOfRay(const Hit& h, const Vec3f& direction,
  const Triangle* triangles, const Vec3f* faceNormals, const LinkParams& p)
{
  RayLinks r;
  if (h.triangle == kInvalidIndex)
  {
    r.environment = true;
    r.count = 1;
    r.column[0] = p.envWidth > 0 ? environmentTexel(p.envWidth, p.envHeight, direction) : 0;
    r.weight[0] = p.weight;
    return r;
  }
  const bool back = dot(direction, faceNormals[h.triangle]) > 0.f;
  if (back && !p.twoSided)
  {
    return r;
  }
  const Triangle tri = triangles[h.triangle];
  Index column[3];
  float weight[3];
  if (p.detail.steps && p.detail.steps[h.triangle] >= 2)
  {
    detailCell(p.detail, h.triangle, tri, h.u, h.v, back, p.vertexCount, column, weight);
  }
  else
  {
    const Index offset = back ? p.vertexCount : 0;
    const float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
    for (int j = 0; j < 3; ++j)
    {
      column[j] = tri.v[j] + offset;
      weight[j] = bary[j];
    }
  }
  for (int j = 0; j < 3; ++j)
  {
    if (weight[j] > 0.f)
    {
      r.column[r.count] = column[j];
      r.weight[r.count] = p.weight * weight[j];
      ++r.count;
    }
  }
  return r;
}

/// Stage 1: shoots raysPerVertex rays from every element.
LinkHits traceLinkRays(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const LinkOptions& options, const ProgressCallback& progress = {});
/// The same into `out`, whose hit buffer is reused when it already has the right size.
void traceLinkRays(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const LinkOptions& options, LinkHits& out,
  const ProgressCallback& progress = {});

/// Stage 2: turns hits into links and merges links with the same (x, y) into CSR rows
/// (each column once per row; columns in first-hit order, not sorted).
LinkStructure compressLinks(const Scene& scene, const LinkHits& hits,
  const std::vector<Vec3f>& faceNormals, const LinkOptions& options,
  const ProgressCallback& progress = {});

/// Stages 1 and 2 element by element: each element's rays are traced and its row compressed
/// at once, so no buffer holds every hit (raysPerVertex x 16 bytes per element) and the
/// compressed rows are kept at their size. The same rows as compressLinks(traceLinkRays()).
/// `msCompress`, when given, receives the compression's share of the wall time.
LinkStructure buildLinks(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const std::vector<Vec3f>& faceNormals, const LinkOptions& options,
  const ProgressCallback& progress = {}, double* msCompress = nullptr);
}
