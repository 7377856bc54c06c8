#include "methods/links/Links.h"
#include "linkgi/Memory.h"

#include "linkgi/Error.h"
#include "shared/Sampling.h"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <chrono>
#include <numeric>

namespace linkgi
{
namespace
{
/// Traces element x's rays - the shared directions in its twisted frame, from its shifted
/// origin - into `hits` (rays.size() of them).
void traceElement(const Scene& scene, const std::vector<RayOrigin>& origins, const std::vector<Vec3f>& dirs,
  const Elements& elements, const LinkOptions& options, std::size_t x,
  const RayTracer& tracer, std::vector<Ray>& rays, Hit* hits)
{
  const Index v = elements.vertexOf(x);
  const Vec3f normal = scene.normals[v] * elements.sideSign(x);
  const Frame frame = vertexFrame(normal, options.twist, options.seed, Index(x));
  const Vec3f origin = elementRayOrigin(scene.positions[v], normal, origins[v]);
  for (std::size_t k = 0; k < rays.size(); ++k)
  {
    rays[k].origin = origin;
    rays[k].direction = frame.toWorld(dirs[k]);
  }
  tracer.trace(rays.data(), hits, rays.size());
}
}

LinkHits traceLinkRays(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const LinkOptions& options, const ProgressCallback& progress)
{
  LinkHits out;
  traceLinkRays(scene, origins, tracer, options, out, progress);
  return out;
}

void traceLinkRays(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const LinkOptions& options, LinkHits& out,
  const ProgressCallback& progress)
{
  const std::vector<Vec3f> dirs = makeDirectionSet(options.raysPerVertex);
  const Elements elements{ scene.vertexCount(), options.twoSided };
  const std::size_t n = dirs.size();
  out.raysPerVertex = options.raysPerVertex;
  // Every hit is overwritten below; a buffer of the right size from the last update is
  // reused as it is (no fill, no fresh pages: that was ~12% of link generation).
  if (out.hits.size() != elements.count() * n)
  {
    out.hits.clear();
    out.hits.resize(elements.count() * n);
  }
  parallelFor("links", elements.count(), 8,
    [&](std::size_t begin, std::size_t end) {
      std::vector<Ray> rays(n);
      for (std::size_t x = begin; x < end; ++x)
      {
        traceElement(scene, origins, dirs, elements, options, x, tracer, rays, &out.hits[x * n]);
      }
    },
    progress);
}

namespace
{
/// One chunk of compressed rows, built by one task.
struct RowChunk
{
  std::vector<Index> columns, envColumns;
  std::vector<float> weights, envWeights;
  std::uint64_t rawLinks = 0;
};

/// Scratch row: accumulates weights by column in a dense array over the elements (or texels)
/// and remembers which columns it touched; links to detail nodes (columns from
/// `value.size()` on) are listed and merged at the flush, so that a worker's scratch does
/// not grow with the nodes.
struct ScratchRow
{
  std::vector<float> value;
  std::vector<Index> touched;
  std::vector<std::pair<Index, float>> beyond;

  void add(Index column, float w)
  {
    if (column >= value.size())
    {
      beyond.emplace_back(column, w);
      return;
    }
    if (value[column] == 0.f)
    {
      touched.push_back(column);
    }
    value[column] += w;
  }
  /// Appends the row to (columns, weights) and clears the scratch. Columns stay in the
  /// order rays first reached them (the nodes' after, by column): coherent enough for the
  /// gather, and sorting them would cost more than the rest of the compression.
  std::size_t flush(std::vector<Index>& columns, std::vector<float>& weights)
  {
    const std::size_t before = columns.size();
    for (Index c : touched)
    {
      columns.push_back(c);
      weights.push_back(value[c]);
      value[c] = 0.f;
    }
    touched.clear();
    // Stable: equal columns add up in ray order, as in the dense part.
    std::stable_sort(beyond.begin(), beyond.end(),
      [](const std::pair<Index, float>& a, const std::pair<Index, float>& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < beyond.size(); ++i)
    {
      if (i > 0 && beyond[i].first == beyond[i - 1].first)
      {
        weights.back() += beyond[i].second;
        continue;
      }
      columns.push_back(beyond[i].first);
      weights.push_back(beyond[i].second);
    }
    beyond.clear();
    return columns.size() - before;
  }
};

/// Appends a band's rows to `m`: their offsets from `rowCounts`, then every chunk's entries
/// copied, in parallel, to where they belong (after the previous bands', within the capacity
/// that linkRows reserved).
void appendBand(const std::vector<RowChunk>& band, std::size_t chunkCount, std::size_t firstRow,
  std::size_t chunkRows, const std::vector<Index>& rowCounts, bool environment, SparseMatrix& m)
{
  const std::size_t lastRow = std::min(rowCounts.size(), firstRow + chunkCount * chunkRows);
  for (std::size_t x = firstRow; x < lastRow; ++x)
  {
    m.rowOffsets[x + 1] = m.rowOffsets[x] + rowCounts[x]; // Offset + Index: no 32-bit wrap
  }
  const std::size_t size = m.rowOffsets[lastRow];
  m.columns.resize(size);
  m.weights.resize(size);
  parallelRanges(chunkCount, 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
    {
      const auto& cols = environment ? band[c].envColumns : band[c].columns;
      const auto& ws = environment ? band[c].envWeights : band[c].weights;
      const Offset first = m.rowOffsets[firstRow + c * chunkRows];
      std::copy(cols.begin(), cols.end(), m.columns.begin() + first);
      std::copy(ws.begin(), ws.end(), m.weights.begin() + first);
    }
  });
}

/// Compresses every element's row from the hits `hitsOf(x, scratch)` gives (a pointer to
/// raysPerVertex hits; `scratch` is the calling thread's buffer) into the CSR rows.
template <typename HitsOf>
LinkStructure linkRows(const Scene& scene, std::uint32_t raysPerVertex,
  const std::vector<Vec3f>& faceNormals, const LinkOptions& options,
  const ProgressCallback& progress, const HitsOf& hitsOf)
{
  const std::vector<Vec3f> dirs = makeDirectionSet(raysPerVertex);
  const Elements elements{ scene.vertexCount(), options.twoSided };
  const std::size_t rows = elements.count(), n = dirs.size();
  const Environment& env = scene.environment;
  const std::size_t texels = env.hasTexture() ? env.texels.size() : 1;
  LinkParams params;
  params.vertexCount = Index(elements.vertexCount);
  params.twoSided = options.twoSided;
  params.weight = kPi / float(n);
  params.envWidth = env.hasTexture() ? env.width : 0;
  params.envHeight = env.hasTexture() ? env.height : 0;
  const std::size_t columns = rows + (options.detail ? options.detail->columns(options.twoSided) : 0);
  if (options.detail)
  {
    params.detail = options.detail->grid(rows);
  }

  // The rows are compressed band by band: a band's chunks in parallel into buffers that
  // are reused for every band (their pages stay resident and warm), then appended to the
  // CSR. Chunks kept until the end and copied into the CSR after cost twice the links'
  // size in fresh pages and a cold copy - a quarter of the compression at 1M vertices.
  // As many bands as parallelFor has slices, so that progress and an abort are asked as
  // often; no more than 512 chunks a band, so that its buffers stay small (about 180 MB at
  // 256 rays).
  constexpr std::size_t kChunkRows = 64;
  const std::size_t chunkCount = (rows + kChunkRows - 1) / kChunkRows;
  const std::size_t bands = progressSlices(chunkCount, 1);
  const std::size_t bandSize = std::min<std::size_t>((chunkCount + bands - 1) / bands, 512);
  std::vector<RowChunk> band(std::min(chunkCount, bandSize));
  std::vector<Index> rowCounts(rows), envRowCounts(rows);
  // Both matrices reserve room for every link the rays could make: address space only until
  // written, and never reallocated, so no band's append copies what came before or holds
  // the links twice.
  LinkStructure out;
  const LinksPerElement bound = LinksPerElement::bound(n, columns, texels);
  for (SparseMatrix* m : { &out.transport, &out.environment })
  {
    const std::size_t entries = rows * (m == &out.transport ? bound.transport : bound.environment);
    m->rowOffsets.assign(rows + 1, 0);
    m->columns.reserve(entries);
    m->weights.reserve(entries);
  }
  for (std::size_t firstChunk = 0; firstChunk < chunkCount; firstChunk += bandSize)
  {
    if (progress && !progress("compress", double(firstChunk) / double(chunkCount)))
    {
      throw Aborted();
    }
    const std::size_t bandChunks = std::min(bandSize, chunkCount - firstChunk);
    parallelRanges(bandChunks, 1, [&](std::size_t begin, std::size_t end) {
      // Scratch rows stay all-zero between rows (flush clears them), so they are only
      // reallocated when the size changes.
      thread_local ScratchRow row, envRow;
      thread_local std::vector<Hit> hitScratch;
      if (row.value.size() != rows)
      {
        row.value.assign(rows, 0.f);
      }
      if (envRow.value.size() != texels)
      {
        envRow.value.assign(texels, 0.f);
      }
      for (std::size_t b = begin; b < end; ++b)
      {
        RowChunk& chunk = band[b];
        chunk.columns.clear(); // the capacity stays
        chunk.weights.clear();
        chunk.envColumns.clear();
        chunk.envWeights.clear();
        const std::size_t c = firstChunk + b;
        for (std::size_t x = c * kChunkRows; x < std::min(rows, (c + 1) * kChunkRows); ++x)
        {
          if (options.rows && !options.rows[x])
          {
            rowCounts[x] = envRowCounts[x] = 0; // another process's row
            continue;
          }
          const Hit* hits = hitsOf(x, hitScratch);
          const Index v = elements.vertexOf(x);
          const Frame frame = vertexFrame(
            scene.normals[v] * elements.sideSign(x), options.twist, options.seed, Index(x));
          for (std::size_t k = 0; k < n; ++k)
          {
            const RayLinks links = linksOfRay(hits[k], frame.toWorld(dirs[k]),
              scene.triangles.data(), faceNormals.data(), params);
            for (int j = 0; j < links.count; ++j)
            {
              (links.environment ? envRow : row).add(links.column[j], links.weight[j]);
            }
            chunk.rawLinks += links.count;
          }
          rowCounts[x] = Index(row.flush(chunk.columns, chunk.weights));
          envRowCounts[x] = Index(envRow.flush(chunk.envColumns, chunk.envWeights));
        }
      }
    });
    const std::size_t firstRow = firstChunk * kChunkRows;
    appendBand(band, bandChunks, firstRow, kChunkRows, rowCounts, false, out.transport);
    appendBand(band, bandChunks, firstRow, kChunkRows, envRowCounts, true, out.environment);
  }
  if (progress && !progress("compress", 1.0))
  {
    throw Aborted();
  }
  const std::size_t linked =
    options.rows ? std::size_t(std::count(options.rows, options.rows + rows, std::uint8_t(1))) : rows;
  out.rays = std::uint64_t(linked) * n;
  for (const RowChunk& chunk : band)
  {
    out.rawLinks += chunk.rawLinks;
  }
  std::vector<RowChunk>().swap(band);
  returnFreedMemory(); // the band's buffers
  return out;
}
}

LinkStructure compressLinks(const Scene& scene, const LinkHits& hits,
  const std::vector<Vec3f>& faceNormals, const LinkOptions& options,
  const ProgressCallback& progress)
{
  const std::size_t n = hits.raysPerVertex;
  return linkRows(scene, hits.raysPerVertex, faceNormals, options, progress,
    [&](std::size_t x, std::vector<Hit>&) { return &hits.hits[x * n]; });
}

LinkStructure buildLinks(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const std::vector<Vec3f>& faceNormals, const LinkOptions& options,
  const ProgressCallback& progress, double* msCompress)
{
  const std::vector<Vec3f> dirs = makeDirectionSet(options.raysPerVertex);
  const Elements elements{ scene.vertexCount(), options.twoSided };
  const std::size_t n = dirs.size();
  std::atomic<std::int64_t> traceNs{ 0 };
  const auto start = std::chrono::steady_clock::now();
  LinkStructure out = linkRows(scene, options.raysPerVertex, faceNormals, options, progress,
    [&](std::size_t x, std::vector<Hit>& hits) {
      const auto t = std::chrono::steady_clock::now();
      thread_local std::vector<Ray> rays;
      rays.resize(n);
      hits.resize(n);
      traceElement(scene, origins, dirs, elements, options, x, tracer, rays, hits.data());
      traceNs += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t).count();
      return hits.data();
    });
  if (msCompress)
  {
    // The threads' tracing time, spread over the workers, is the wall time they traced.
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double tracing = double(traceNs.load()) * 1e-6 / double(std::max(1, workerCount()));
    *msCompress = std::max(0.0, wall - tracing);
  }
  return out;
}
}
