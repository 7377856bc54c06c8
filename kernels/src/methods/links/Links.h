// Link generation and compression: the vertex-to-vertex transport matrix W.
#pragma once

#include "shared/NoFillVector.h"
#include "cpu/Parallel.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "linkgi/Scene.h"
#include "scene/Topology.h"

#include <algorithm>
#include <cstdint>
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

/// Rows of a CSR matrix as the gather reads them: row r is entries [rowOffsets[r],
/// rowOffsets[r + 1]) counted from `firstEntry`, which columns[0] / weights[0] hold (0 for a
/// whole matrix; a slice of a larger one starts further on).
struct CsrRows
{
  const Offset* rowOffsets = nullptr; ///< rows + 1
  const Index* columns = nullptr;
  const float* weights = nullptr;
  std::size_t rows = 0;
  Offset firstEntry = 0;
};

/// Sparse matrix in CSR form; row = receiving element. Entry offsets are 64-bit (Offset).
struct SparseMatrix
{
  std::vector<Offset> rowOffsets; ///< rows + 1
  /// Not zero-filled on resize(): the link compression writes every entry, in parallel.
  NoFillVector<Index> columns;
  NoFillVector<float> weights;
  std::size_t rows() const { return rowOffsets.empty() ? 0 : rowOffsets.size() - 1; }
  std::size_t nonZeros() const { return columns.size(); }
  std::size_t bytes() const
  {
    return rowOffsets.size() * sizeof(Offset) + columns.size() * sizeof(Index) +
      weights.size() * sizeof(float);
  }
  CsrRows view() const { return { rowOffsets.data(), columns.data(), weights.data(), rows(), 0 }; }
};

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

/// offsets[0] = first, offsets[i + 1] = offsets[i] + counts[i]: row offsets from per-row
/// entry counts, in 64 bits (the sum passes 2^32 on large meshes). offsets gets counts + 1.
void exclusiveOffsets(const std::vector<Index>& counts, Offset first, std::vector<Offset>& offsets);

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
};

/// The links one ray adds to its element's row: up to three (element, weight) pairs for a
/// hit (barycentric weights, back sides offset by vertexCount), one environment texel for a
/// miss, none for a back-face hit on one-sided elements (the ray is blocked and sees black).
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
  const Index offset = back ? p.vertexCount : 0;
  const Triangle tri = triangles[h.triangle];
  const float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
  for (int j = 0; j < 3; ++j)
  {
    if (bary[j] > 0.f)
    {
      r.column[r.count] = tri.v[j] + offset;
      r.weight[r.count] = p.weight * bary[j];
      ++r.count;
    }
  }
  return r;
}

/// A triangle's front-side normal (see frontFaceNormals).
LINKGI_HOST_DEVICE inline Vec3f frontFaceNormal(const Vec3f* positions, const Vec3f* normals, const Triangle& t)
{
  const Vec3f& a = positions[t.v[0]];
  const Vec3f n = normalize(cross(positions[t.v[1]] - a, positions[t.v[2]] - a));
  const Vec3f vertexSum = normals[t.v[0]] + normals[t.v[1]] + normals[t.v[2]];
  return dot(n, vertexSum) < 0.f ? -n : n;
}

/// Lenv(j): the radiance of each environment texel the matrix Wenv gathers (one entry, the
/// colour, for a constant environment; colour x texel for a lat-long map).
std::vector<Vec3f> environmentTexelRadiance(const Environment& environment);

/// Front-side normal of each triangle: the winding normal, flipped where it disagrees with
/// the sum of its vertex normals (so inconsistent winding does not turn surfaces black).
std::vector<Vec3f> frontFaceNormals(const Scene& scene);

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
