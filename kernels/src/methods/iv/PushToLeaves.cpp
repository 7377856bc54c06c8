// Push to the leaves (ImplicitLinks.h pushToLeaves): every leaf's row of the transport and
// environment matrices from the node links of its ancestors, keeping the shortest link per
// direction bin. Split from ImplicitLinks.cpp, which creates the node links.
#include "methods/iv/ImplicitLinks.h"
#include "scene/Topology.h"
#include "shared/Gaps.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>

namespace linkgi::iv
{
namespace
{
/// Rows [begin, end) of a matrix, built by one task.
struct RowSlice
{
  std::vector<Index> counts, columns, envCounts, envColumns;
  std::vector<float> weights, envWeights;
};

/// Sorts one row's (column, weight) entries by column and merges equal columns.
void mergeRow(std::vector<std::pair<Index, float>>& row, std::vector<Index>& columns,
  std::vector<float>& weights, std::vector<Index>& counts)
{
  std::sort(row.begin(), row.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  Index count = 0;
  for (std::size_t i = 0; i < row.size(); ++i)
  {
    if (i > 0 && row[i].first == row[i - 1].first)
    {
      weights.back() += row[i].second;
      continue;
    }
    columns.push_back(row[i].first);
    weights.push_back(row[i].second);
    ++count;
  }
  counts.push_back(count);
  row.clear();
}

void concatenate(const std::vector<RowSlice>& slices, bool environment, SparseMatrix& m)
{
  std::vector<Index> counts;
  for (const RowSlice& s : slices)
  {
    const auto& c = environment ? s.envCounts : s.counts;
    counts.insert(counts.end(), c.begin(), c.end());
  }
  exclusiveOffsets(counts, 0, m.rowOffsets);
  m.columns.clear();
  m.weights.clear();
  m.columns.reserve(m.rowOffsets.back());
  m.weights.reserve(m.rowOffsets.back());
  for (const RowSlice& s : slices)
  {
    const auto& c = environment ? s.envColumns : s.columns;
    const auto& w = environment ? s.envWeights : s.weights;
    m.columns.insert(m.columns.end(), c.begin(), c.end());
    m.weights.insert(m.weights.end(), w.begin(), w.end());
  }
}

/// Where a bin's surface hit lies: its triangle and barycentrics (1 - u - v, u, v), read
/// where the triangle carries detail nodes.
struct SurfacePoint
{
  Index triangle = kInvalidIndex;
  float u = 0.f, v = 0.f;
};

/// Whether a surface hit at `at` reads detail nodes: its triangle has a grid.
inline bool onDetailNodes(const DetailGrid& grid, const SurfacePoint& at)
{
  return grid.steps && at.triangle != kInvalidIndex && grid.steps[at.triangle] > 0;
}

/// Offers the hit `source` (flagged kSurfaceHit, and kSurfaceBack for a back) at distance
/// t and point `at` to bin b.
inline void offerHit(std::size_t b, float t, Index source, const SurfacePoint& at, std::vector<float>& bestDistance,
  std::vector<Index>& bestSource, std::vector<SurfacePoint>& bestPoint)
{
  const float d2 = t * t;
  if (bestSource[b] == kInvalidIndex || d2 < bestDistance[b] || (d2 == bestDistance[b] && source < bestSource[b]))
  {
    bestDistance[b] = d2;
    bestSource[b] = source;
    bestPoint[b] = at;
  }
}

/// The bounds of what the pyramid of cube face `face` (about the cube's centre) holds of
/// the triangle q, in that face's coordinates (cubeFace's u, v): the triangle clipped by the
/// pyramid's four planes (Sutherland-Hodgman; at most seven corners). False where it holds
/// none of it.
bool faceBounds(const Vec3f q[3], int face, float& u0, float& u1, float& v0, float& v1)
{
  const int a = face / 2, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
  const float s = face % 2 == 0 ? 1.f : -1.f;
  Vec3f poly[8] = { q[0], q[1], q[2] }, next[8];
  int count = 3;
  const int planes[4][2] = { { b, 1 }, { b, -1 }, { c, 1 }, { c, -1 } };
  for (const auto& plane : planes)
  {
    // Inside: s p[a] - sign p[axis] >= 0.
    const auto g = [&](const Vec3f& x) { return s * x[a] - float(plane[1]) * x[plane[0]]; };
    int kept = 0;
    for (int i = 0; i < count; ++i)
    {
      const Vec3f& p = poly[i];
      const Vec3f& q2 = poly[(i + 1) % count];
      const float gp = g(p), gq = g(q2);
      if (gp >= 0.f)
      {
        next[kept++] = p;
      }
      if ((gp >= 0.f) != (gq >= 0.f))
      {
        next[kept++] = p + (q2 - p) * (gp / (gp - gq));
      }
    }
    count = kept;
    std::copy(next, next + count, poly);
    if (count == 0)
    {
      return false;
    }
  }
  u0 = v0 = 1.f;
  u1 = v1 = -1.f;
  for (int i = 0; i < count; ++i)
  {
    const float m = s * poly[i][a];
    if (!(m > 0.f))
    {
      u0 = v0 = -1.f; // a corner at the cube's centre: the whole face
      u1 = v1 = 1.f;
      return true;
    }
    const float u = poly[i][b] / m, v = poly[i][c] / m;
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  return true;
}

/// Leaves whose discs would misplace their surface (leafReach: near ones, wide ones seen
/// from behind) drawn from their triangles: every bin of the hemisphere about n whose
/// centre ray from o meets one takes it at the hit's distance, its back as such. Only the
/// bins within the columns and rows that the triangle's central projection covers on each
/// cube face are tried (faceBounds).
void drawSurfaces(const Scene& scene, const std::vector<Vec3f>& faceNormals, const ElementTriangles& elements,
  const std::vector<Index>& leaves, const Vec3f& o, const Vec3f& n, const CubeBins& bins,
  std::vector<float>& bestDistance, std::vector<Index>& bestSource, std::vector<SurfacePoint>& bestPoint)
{
  const int side = bins.n;
  for (Index src : leaves)
  {
    for (Index k = elements.offsets[src]; k < elements.offsets[src + 1]; ++k)
    {
      const Triangle& tri = scene.triangles[elements.triangles[k]];
      const Vec3f& front = faceNormals[elements.triangles[k]];
      const Vec3f p[3] = { scene.positions[tri.v[0]], scene.positions[tri.v[1]], scene.positions[tri.v[2]] };
      const int corner = tri.v[0] == src ? 0 : tri.v[1] == src ? 1 : 2;
      const auto tryBin = [&](std::size_t b) {
        const Vec3f& dir = bins.center[b];
        bool back = false;
        SurfacePoint at{ elements.triangles[k] };
        const float t = dot(dir, n) > 0.f ? surfaceHit(o, dir, p[0], p[1], p[2], corner, front, back, at.u, at.v) : -1.f;
        if (t > 0.f)
        {
          offerHit(b, t, src | kSurfaceHit | (back ? kSurfaceBack : 0u), at, bestDistance, bestSource, bestPoint);
        }
      };
      const Vec3f q[3] = { p[0] - o, p[1] - o, p[2] - o };
      float u[3], v[3];
      int faces[3];
      for (int i = 0; i < 3; ++i)
      {
        faces[i] = cubeFace(q[i], u[i], v[i]);
      }
      // Corners on one face: the face's pyramid is convex, so it holds the whole triangle,
      // whose projection is the triangle of the corners' projections.
      const bool oneFace = faces[0] == faces[1] && faces[0] == faces[2];
      for (int face = oneFace ? faces[0] : 0; face < (oneFace ? faces[0] + 1 : 6); ++face)
      {
        float u0 = std::min({ u[0], u[1], u[2] }), u1 = std::max({ u[0], u[1], u[2] });
        float v0 = std::min({ v[0], v[1], v[2] }), v1 = std::max({ v[0], v[1], v[2] });
        if (!oneFace && !faceBounds(q, face, u0, u1, v0, v1))
        {
          continue;
        }
        const int c0 = cubeCell(u0, side), c1 = cubeCell(u1, side);
        const int r0 = cubeCell(v0, side), r1 = cubeCell(v1, side);
        for (int row = r0; row <= r1; ++row)
        {
          for (int col = c0; col <= c1; ++col)
          {
            tryBin((std::size_t(face) * side + row) * side + col);
          }
        }
      }
    }
  }
}

/// Bins whose surface hit, at the receiver's `origin`, lies in a gap that the hit leaf's
/// vertex is not in (hitInGap): black, as a back. Not a hit on a triangle with detail nodes
/// (`grid`): it reads the nodes around the hit, not the vertex.
void darkenGaps(const ClusterTree& tree, const std::vector<Vec3f>& faceNormals, const std::vector<RayOrigin>& receivers,
  const RayTracer& tracer, const DetailGrid& grid, const Vec3f& origin, const Vec3f& n, const CubeBins& bins,
  const std::vector<float>& bestDistance, std::vector<Index>& bestSource, const std::vector<SurfacePoint>& bestPoint)
{
  const ClosestHit trace{ tracer };
  for (std::size_t b = 0; b < bins.count(); ++b)
  {
    const Index hit = bestSource[b];
    const Vec3f& dir = bins.center[b];
    if (hit == kInvalidIndex || !(hit & kSurfaceHit) || (hit & kSurfaceBack) || dot(n, dir) <= 0.f ||
      onDetailNodes(grid, bestPoint[b]))
    {
      continue;
    }
    const Index src = hit & kSourceMask;
    const float t = std::sqrt(bestDistance[b]);
    const Vec3f facing = dot(tree.normal[src], dir) < 0.f ? tree.normal[src] : -tree.normal[src];
    if (hitInGap(faceNormals.data(), origin + dir * t, tree.position[src], facing, t, receivers[src].offset, trace))
    {
      bestSource[b] = hit | kSurfaceBack;
    }
  }
}
}

ElementTriangles ElementTriangles::of(const Scene& scene)
{
  ElementTriangles e;
  incidentTriangles(scene.vertexCount(), scene.triangles, e.offsets, e.triangles);
  return e;
}

LeafLinks pushToLeaves(const ClusterTree& tree, const NodeLinks& links, const CubeBins& bins,
  const Scene& scene, const std::vector<Vec3f>& faceNormals, const ElementTriangles& elements,
  const std::vector<RayOrigin>& receivers, const RayTracer* tracer, const DetailNodes& detail,
  const ProgressCallback& progress, const std::uint8_t* rows)
{
  const std::size_t leaves = tree.leafCount, nb = bins.count();
  if (tree.nodeCount() > kSourceMask)
  {
    throw Error("The implicit-visibility method holds at most " + std::to_string(kSourceMask / 2) +
      " vertices; the scene has " + std::to_string(leaves) + ".");
  }
  const Environment& environment = scene.environment;
  const std::size_t sliceCount = std::min<std::size_t>(leaves, std::size_t(workerCount()) * 16);
  std::vector<RowSlice> slices(sliceCount);
  std::vector<std::uint64_t> occupied(sliceCount, 0), empty(sliceCount, 0);
  const SparseMatrix& m = links.byReceiver;
  const float binAngle = std::sqrt(bins.meanSolidAngle());
  // A link keeps the bin it has at its receiving node (below), whichever leaf it is pushed
  // to: one cube-bin lookup per link instead of one per link and leaf beneath it.
  std::vector<Index> binTexel(nb); // the environment texel each bin's centre sees
  for (std::size_t b = 0; b < nb; ++b)
  {
    binTexel[b] = environment.texelIndex(bins.center[b]);
  }
  const DetailGrid grid = detail.grid(tree.nodeCount()); // node columns after the tree's
  std::vector<int> linkBin(m.nonZeros(), -1);
  parallelRanges(m.rows(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t node = begin; node < end; ++node)
    {
      for (Offset e = m.rowOffsets[node]; e < m.rowOffsets[node + 1]; ++e)
      {
        const Vec3f d = tree.position[m.columns[e]] - tree.position[node];
        linkBin[e] = dot(d, d) > 0.f ? cubeBin(d, bins.n) : -1;
      }
    }
  });
  parallelFor("ImplicitLinks", sliceCount, 1, [&](std::size_t first, std::size_t last) {
    std::vector<float> bestDistance(nb);
    std::vector<Index> bestSource(nb, kInvalidIndex);
    std::vector<SurfacePoint> bestPoint(nb);
    std::vector<std::pair<Index, float>> row, envRow;
    std::vector<Index> surfaces;
    for (std::size_t s = first; s < last; ++s)
    {
      RowSlice& out = slices[s];
      // Local counts: neighbouring slices' counters share a cache line.
      std::uint64_t occupiedHere = 0, emptyHere = 0;
      for (std::size_t leaf = s * leaves / sliceCount; leaf < (s + 1) * leaves / sliceCount; ++leaf)
      {
        if (rows && !rows[leaf])
        {
          out.counts.push_back(0); // another process's row
          out.envCounts.push_back(0);
          continue;
        }
        const Vec3f n = tree.normal[leaf];
        const Vec3f p = receivers.empty() ? tree.position[leaf] : tree.position[leaf] + receivers[leaf].shift;
        for (Index node = Index(leaf); node != kInvalidIndex; node = tree.parent[node])
        {
          for (Offset e = m.rowOffsets[node]; e < m.rowOffsets[node + 1]; ++e)
          {
            const Index src = m.columns[e];
            // `bin` >= 0: the point's bin is known (the link's own at an ancestor node).
            const auto offer = [&](const Vec3f& q, int bin) {
              const Vec3f d = q - p;
              const float d2 = dot(d, d);
              if (!(d2 > 0.f) || dot(n, d) <= 0.f)
              {
                return; // behind this leaf's plane, though its ancestor could see it
              }
              // A link pushed down keeps the bin it has at its node (as in the paper): a
              // node's bins hold one link each, and re-binning from the leaf would leave
              // holes between them.
              if (bin < 0)
              {
                const Vec3f binned = node == leaf ? d : q - tree.position[node];
                bin = cubeBin(dot(binned, binned) > 0.f ? binned : d, bins.n);
              }
              if (bestSource[bin] == kInvalidIndex || d2 < bestDistance[bin] ||
                (d2 == bestDistance[bin] && src < bestSource[bin]))
              {
                bestDistance[bin] = d2;
                bestSource[bin] = src;
              }
            };
            offer(tree.position[src], node == leaf ? -1 : linkBin[e]);
            if (tree.isLeaf(src))
            {
              const Vec3f toSource = tree.position[src] - p;
              const float r2 = dot(toSource, toSource), radius = tree.radius[src];
              const LeafReach reach = leafReach(radius, tree.extent[src], r2, binAngle, -dot(tree.normal[src], toSource));
              if (reach == LeafReach::Surface)
              {
                surfaces.push_back(src); // a neighbour, a twin, a surface across a contact or behind
              }
              else if (reach == LeafReach::Splat)
              {
                auto point = [&](const Vec3f& q) { offer(q, -1); };
                splatDisc(tree.position[src], tree.normal[src], radius, std::sqrt(r2), binAngle, point);
              }
            }
          }
        }
        // A leaf linked from several of its ancestors is drawn once.
        std::sort(surfaces.begin(), surfaces.end());
        surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
        const Vec3f origin = receivers.empty() ? p : p + n * receivers[leaf].offset;
        drawSurfaces(scene, faceNormals, elements, surfaces, origin, n, bins, bestDistance, bestSource, bestPoint);
        if (tracer && !surfaces.empty() && !receivers.empty())
        {
          darkenGaps(tree, faceNormals, receivers, *tracer, grid, origin, n, bins, bestDistance, bestSource, bestPoint);
        }
        surfaces.clear();
        float hemisphere = 0.f;
        for (std::size_t b = 0; b < nb; ++b)
        {
          const float c = dot(n, bins.center[b]);
          const Index src = bestSource[b];
          bestSource[b] = kInvalidIndex;
          if (c <= 0.f)
          {
            continue;
          }
          const float w = bins.solidAngle[b] * c;
          hemisphere += w;
          if (src == kInvalidIndex)
          {
            envRow.emplace_back(binTexel[b], w);
            ++emptyHere;
            continue;
          }
          ++occupiedHere;
          // A surface hit shows the side it was met on; otherwise the side the disc faces.
          const bool front = (src & kSurfaceHit) ? !(src & kSurfaceBack)
                                                 : dot(tree.normal[src], p - tree.position[src]) > 0.f;
          if (!front)
          {
            continue;
          }
          if ((src & kSurfaceHit) && onDetailNodes(grid, bestPoint[b]))
          {
            // A hit on a triangle with detail nodes: the grid point nearest to it, one entry
            // per bin as any other source's.
            const SurfacePoint& at = bestPoint[b];
            row.emplace_back(detailNearestColumn(grid, at.triangle, scene.triangles[at.triangle], at.u, at.v, false,
                               Index(leaves)),
              w);
          }
          else
          {
            row.emplace_back(src & kSourceMask, w);
          }
        }
        const float scale = hemisphere > 0.f ? kPi / hemisphere : 0.f;
        for (auto* r : { &row, &envRow })
        {
          for (auto& entry : *r)
          {
            entry.second *= scale;
          }
        }
        mergeRow(row, out.columns, out.weights, out.counts);
        mergeRow(envRow, out.envColumns, out.envWeights, out.envCounts);
      }
      occupied[s] = occupiedHere;
      empty[s] = emptyHere;
    }
  }, [&progress](const char*, double f) { return !progress || progress("ImplicitLinks", f); });
  LeafLinks result;
  concatenate(slices, false, result.transport);
  concatenate(slices, true, result.environment);
  for (std::size_t s = 0; s < sliceCount; ++s)
  {
    result.occupiedBins += occupied[s];
    result.emptyBins += empty[s];
  }
  return result;
}
}
