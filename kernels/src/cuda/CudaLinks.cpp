// The link stage of the CUDA engine: the element range in batches across all devices,
// each batch sized by its device's speed on its previous batch (paper, sec. 3.2), traced and
// compressed where it was traced; the rows are then merged into one CSR on the first device.
#include "EngineDevice.h"
#include "Primitives.h"

#include "linkgi/Sampling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

namespace linkgi::cuda
{
namespace
{
/// Hands out element ranges. A device's batch takes about `targetMs` at its last measured
/// speed; once what is left would not fill one more round, the rest is split in proportion
/// to the speeds so all devices finish together.
class BatchScheduler
{
public:
  BatchScheduler(Index total, std::vector<EngineDevice*> devices, Index maxBatch)
    : total(total), devices(std::move(devices)), maxBatch(maxBatch)
  {
  }

  bool next(std::size_t device, Index& first, Index& count)
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (cursor >= total || stop)
    {
      return false;
    }
    const Index left = total - cursor;
    double speedSum = 0.0;
    bool allMeasured = true;
    for (EngineDevice* d : devices)
    {
      speedSum += d->elementsPerMs;
      allMeasured = allMeasured && d->elementsPerMs > 0.0;
    }
    Index size;
    if (devices.size() == 1)
    {
      size = left;
    }
    else if (!allMeasured)
    {
      size = std::max<Index>(1024, total / Index(8 * devices.size())); // a first measurement
    }
    else
    {
      const double speed = devices[device]->elementsPerMs;
      if (finalLeft == 0 && left > speedSum * kTargetMs)
      {
        size = Index(speed * kTargetMs);
      }
      else
      {
        // The last round: each device's share of what was left when it began, in
        // proportion to its speed, so that all finish at about the same time.
        finalLeft = finalLeft ? finalLeft : left;
        size = Index(std::ceil(finalLeft * speed / speedSum));
      }
    }
    count = std::max<Index>(1, std::min({ size, left, maxBatch }));
    first = cursor;
    cursor += count;
    return true;
  }

  void cancel()
  {
    std::lock_guard<std::mutex> lock(mutex);
    stop = true;
  }

private:
  static constexpr double kTargetMs = 4.0;
  std::mutex mutex;
  Index total, cursor = 0, finalLeft = 0;
  std::vector<EngineDevice*> devices;
  Index maxBatch;
  bool stop = false;
};

struct LinkJob
{
  LinkCompressParams params;
  Index elements = 0;
};

/// Largest batch whose scratch fits in about half of the device's free memory.
Index maxBatchFor(const EngineDevice& d, Index raysPerVertex)
{
  std::size_t freeBytes = 0, totalBytes = 0;
  LINKGI_CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes));
  const std::size_t perElement = std::size_t(raysPerVertex) *
      (sizeof(LinkHit) + 3 * (sizeof(Index) + sizeof(float)) + sizeof(Index) + sizeof(float)) +
    64;
  return Index(std::max<std::size_t>(256, (freeBytes + d.scratch.bytes()) / 2 / perElement));
}

/// Traces and compresses elements [first, first + count) on `d`, appending the rows to its
/// arena.
LinkPiece linkBatch(EngineDevice& d, const LinkJob& job, Index first, Index count)
{
  const Index n = job.params.trace.raysPerVertex;
  LinkScratch& s = d.scratch;
  s.hits.resize(std::size_t(count) * n);
  s.columns.resize(std::size_t(count) * 3 * n);
  s.weights.resize(std::size_t(count) * 3 * n);
  s.envColumns.resize(std::size_t(count) * n);
  s.envWeights.resize(std::size_t(count) * n);
  s.counts.resize(count);
  s.envCounts.resize(count);
  s.offsets.resize(count);

  LinkCompressParams p = job.params;
  p.trace.bvh = d.bvh.view();
  p.trace.positions = d.positions.data();
  p.trace.normals = d.normals.data();
  p.trace.shifts = d.shifts.data();
  p.trace.directions = d.directions.data();
  p.trace.firstElement = first;
  p.trace.elementCount = count;
  p.triangles = d.triangles.data();
  p.faceNormals = d.faceNormals.data();

  LINKGI_CUDA_CHECK(cudaEventRecord(d.events[0], d.stream));
  traceLinks(p.trace, s.hits.data(), d.stream);
  LINKGI_CUDA_CHECK(cudaEventRecord(d.events[1], d.stream));
  LinkRowsOut out{ s.columns.data(), s.weights.data(), s.counts.data(), s.envColumns.data(),
    s.envWeights.data(), s.envCounts.data(), s.rawLinks.data() };
  compressLinks(p, s.hits.data(), out, d.stream);

  LinkPiece piece;
  piece.first = first;
  piece.count = count;
  LinkArena& a = d.arena;
  // Transport rows, then environment rows: scan the counts, read the total, append.
  for (int env = 0; env < 2; ++env)
  {
    const Index* counts = env ? s.envCounts.data() : s.counts.data();
    exclusiveSum(counts, s.offsets.data(), count, s.temp, d.stream);
    Index last[2] = { 0, 0 };
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(&last[0], s.offsets.data() + count - 1, sizeof(Index),
      cudaMemcpyDeviceToHost, d.stream));
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(&last[1], counts + count - 1, sizeof(Index),
      cudaMemcpyDeviceToHost, d.stream));
    d.sync();
    const Index nnz = last[0] + last[1];
    GPUBuffer<Index>& columns = env ? a.envColumns : a.columns;
    GPUBuffer<float>& weights = env ? a.envWeights : a.weights;
    GPUBuffer<Index>& rowCounts = env ? a.envCounts : a.counts;
    const std::size_t base = columns.size(), rowBase = rowCounts.size();
    columns.growKeep(base + nnz, d.stream);
    weights.growKeep(base + nnz, d.stream);
    rowCounts.growKeep(rowBase + count, d.stream);
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(rowCounts.data() + rowBase, counts, count * sizeof(Index),
      cudaMemcpyDeviceToDevice, d.stream));
    packRows(env ? s.envColumns.data() : s.columns.data(), env ? s.envWeights.data() : s.weights.data(),
      env ? n : 3 * n, counts, s.offsets.data(), count, columns.data() + base, weights.data() + base,
      d.stream);
    (env ? piece.envBase : piece.base) = base;
    (env ? piece.envNonZeros : piece.nonZeros) = nnz;
    piece.rowBase = rowBase; // the same for both: one row count per element in each
  }
  LINKGI_CUDA_CHECK(cudaEventRecord(d.events[2], d.stream));
  d.sync();
  float trace = 0.f, compress = 0.f;
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&trace, d.events[0], d.events[1]));
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&compress, d.events[1], d.events[2]));
  d.msTrace += trace;
  d.msCompress += compress;
  d.elementsPerMs = count / std::max(1e-3, double(trace + compress));
  return piece;
}

/// Concatenates the pieces (in element order) into `m` on the first device.
void mergePieces(EngineDevice& d0, const std::vector<EngineDevice*>& devices,
  std::vector<LinkPiece> pieces, Index rows, bool env, DeviceCsr& m)
{
  d0.use();
  std::sort(pieces.begin(), pieces.end(), [](const LinkPiece& a, const LinkPiece& b) { return a.first < b.first; });
  Index total = 0;
  for (const LinkPiece& p : pieces)
  {
    total += env ? p.envNonZeros : p.nonZeros;
  }
  m.rowOffsets.resize(std::size_t(rows) + 1);
  d0.rowCounts.resize(std::max<Index>(rows, 1));
  for (const LinkPiece& p : pieces)
  {
    const LinkArena& a = devices[p.device]->arena;
    LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(d0.rowCounts.data() + p.first, d0.id,
      (env ? a.envCounts : a.counts).data() + p.rowBase, devices[p.device]->id,
      p.count * sizeof(Index), d0.stream));
  }
  exclusiveSum(d0.rowCounts.data(), m.rowOffsets.data(), rows, d0.temp, d0.stream);
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(m.rowOffsets.data() + rows, &total, sizeof(Index),
    cudaMemcpyHostToDevice, d0.stream));
  LinkArena& a0 = d0.arena;
  if (devices.size() == 1 || (pieces.size() == 1 && pieces[0].device == 0))
  {
    // Everything is already in order in the first device's arena: swap, don't copy (the
    // old matrix's buffers become the arena of the next link stage).
    m.columns.swapWith(env ? a0.envColumns : a0.columns);
    m.weights.swapWith(env ? a0.envWeights : a0.weights);
    m.columns.growKeep(total, d0.stream);
    m.weights.growKeep(total, d0.stream);
  }
  else
  {
    m.columns.resize(total);
    m.weights.resize(total);
    Index at = 0;
    for (const LinkPiece& p : pieces)
    {
      const LinkArena& a = devices[p.device]->arena;
      const Index nnz = env ? p.envNonZeros : p.nonZeros;
      const std::size_t from = env ? p.envBase : p.base;
      const int src = devices[p.device]->id;
      if (nnz)
      {
        LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(m.columns.data() + at, d0.id,
          (env ? a.envColumns : a.columns).data() + from, src, nnz * sizeof(Index), d0.stream));
        LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(m.weights.data() + at, d0.id,
          (env ? a.envWeights : a.weights).data() + from, src, nnz * sizeof(float), d0.stream));
      }
      at += nnz;
    }
  }
  d0.sync(); // `total` lives on this stack frame
}
}

void Engine::buildLinks(const HostInputs& in, const SolverOptions& options, SolverStats& stats,
  const ProgressCallback& progress)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const Scene& s = in.scene;
  const Elements elements{ s.vertexCount(), options.twoSided };
  const Index ne = Index(elements.count());
  const std::vector<Vec3f> dirs = makeDirectionSet(options.raysPerVertex);
  LinkJob job;
  job.elements = ne;
  LinkTraceParams& t = job.params.trace;
  t.raysPerVertex = options.raysPerVertex;
  t.vertexCount = Index(s.vertexCount());
  t.twist = options.twist;
  t.seed = options.seed;
  t.eps = rayEpsilon(s);
  job.params.twoSided = options.twoSided;
  job.params.envWidth = s.environment.hasTexture() ? s.environment.width : 0;
  job.params.envHeight = s.environment.hasTexture() ? s.environment.height : 0;

  std::vector<EngineDevice*> all;
  Index maxBatch = ne;
  for (auto& d : devices)
  {
    d->use();
    d->directions.upload(dirs, d->stream);
    d->scratch.rawLinks.resize(1);
    d->scratch.rawLinks.fillZero(d->stream);
    d->pieces.clear();
    d->arena.clear();
    d->msTrace = d->msCompress = 0.0;
    maxBatch = std::min(maxBatch, maxBatchFor(*d, options.raysPerVertex));
    all.push_back(d.get());
  }
  BatchScheduler scheduler(ne, all, std::max<Index>(1, maxBatch));

  // Devices after the first run on their own threads; the first runs here, between batches
  // asking `progress` (which may touch GUI state, so only from this thread).
  std::vector<std::exception_ptr> errors(devices.size());
  std::atomic<Index> done{ 0 };
  const auto work = [&](std::size_t i, bool ask) {
    try
    {
      EngineDevice& d = *devices[i];
      d.use();
      Index first = 0, count = 0;
      while (scheduler.next(i, first, count))
      {
        d.pieces.push_back(linkBatch(d, job, first, count));
        d.pieces.back().device = int(i);
        done += count;
        if (ask && progress && !progress("links", 0.75 * double(done) / std::max<Index>(ne, 1)))
        {
          throw Aborted();
        }
      }
    }
    catch (...)
    {
      errors[i] = std::current_exception();
      scheduler.cancel();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t i = 1; i < devices.size(); ++i)
  {
    threads.emplace_back(work, i, false);
  }
  work(0, true);
  for (std::thread& th : threads)
  {
    th.join();
  }
  for (const std::exception_ptr& e : errors)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }

  const auto merge = clock::now();
  std::vector<LinkPiece> pieces;
  linked.assign(devices.size(), 0);
  rawLinks = 0;
  double msCompress = 0.0;
  for (std::size_t i = 0; i < devices.size(); ++i)
  {
    EngineDevice& d = *devices[i];
    for (const LinkPiece& p : d.pieces)
    {
      pieces.push_back(p);
      linked[i] += p.count;
    }
    d.use();
    unsigned long long raw = 0;
    d.scratch.rawLinks.download(&raw, 1);
    rawLinks += raw;
    msCompress = std::max(msCompress, d.msCompress);
  }
  EngineDevice& d0 = *devices[0];
  mergePieces(d0, all, pieces, ne, false, d0.transport);
  mergePieces(d0, all, pieces, ne, true, d0.environment);
  rays = std::uint64_t(ne) * options.raysPerVertex;
  const double msMerge = std::chrono::duration<double, std::milli>(clock::now() - merge).count();
  const double msAll = std::chrono::duration<double, std::milli>(clock::now() - start).count();
  stats.msCompress = msCompress + msMerge;
  stats.msLinks = std::max(0.0, msAll - stats.msCompress);
}
}
