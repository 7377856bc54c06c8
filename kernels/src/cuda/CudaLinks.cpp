// The link stage of the CUDA engine: the element range in batches across all devices,
// each batch sized by its device's speed on its previous batch (paper, sec. 3.2), traced and
// compressed where it was traced, and its rows written straight into the first device's
// matrix (peer stores over NVLink), so the devices' results need no merge pass.
#include "EngineDevice.h"
#include "Primitives.h"

#include "linkgi/Sampling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>

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
  BatchScheduler(Index total, std::vector<EngineDevice*> devices)
    : total(total), devices(std::move(devices)), maxBatch(this->devices.size(), total)
  {
  }

  /// The largest batch `device` has memory for.
  void limit(std::size_t device, Index most)
  {
    std::lock_guard<std::mutex> lock(mutex);
    maxBatch[device] = std::max<Index>(1, most);
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
      size = std::max<Index>(1024, total / Index(4 * devices.size())); // a first measurement
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
    count = std::max<Index>(1, std::min({ size, left, maxBatch[device] }));
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
  static constexpr double kTargetMs = 8.0;
  std::mutex mutex;
  Index total, cursor = 0, finalLeft = 0;
  std::vector<EngineDevice*> devices;
  std::vector<Index> maxBatch;
  bool stop = false;
};

struct LinkJob
{
  LinkCompressParams params;
  Index elements = 0;
};

/// The first device's matrices and the next free entry of each, shared by all devices.
class MatrixSink
{
public:
  MatrixSink(EngineDevice& first) : first(first) {}
  /// Room for a batch's entries: returns where they start in W and Wenv.
  void reserve(Index nnz, Index envNnz, Index& base, Index& envBase)
  {
    std::lock_guard<std::mutex> lock(mutex);
    base = used;
    envBase = envUsed;
    used += nnz;
    envUsed += envNnz;
  }
  PackedRows target(bool env) const
  {
    DeviceCsr& m = env ? first.environment : first.transport;
    return PackedRows{ m.columns.data(), m.weights.data(), m.rowStarts.data(), m.rowCounts.data(), 0, 0 };
  }
  int device() const { return first.id; }
  Index used = 0, envUsed = 0;

private:
  EngineDevice& first;
  std::mutex mutex;
};

/// Largest batch whose scratch fits in about half of the device's free memory.
Index maxBatchFor(const EngineDevice& d, Index raysPerVertex)
{
  std::size_t freeBytes = 0, totalBytes = 0;
  LINKGI_CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes));
  const std::size_t perElement = std::size_t(raysPerVertex) *
      (sizeof(LinkHit) + 4 * (sizeof(Index) + sizeof(float))) + 64;
  return Index(std::max<std::size_t>(256, (freeBytes + d.scratch.bytes()) / 2 / perElement));
}

/// Packs a batch's rows into the sink: directly where the device may write the first
/// device's memory, else into staging buffers and copied over.
void packInto(EngineDevice& d, MatrixSink& sink, bool env, Index n, Index first, Index count,
  Index base, Index nnz)
{
  LinkScratch& s = d.scratch;
  const Index* counts = env ? s.envCounts.data() : s.counts.data();
  const Index* offsets = env ? s.envOffsets.data() : s.offsets.data();
  const Index* columns = env ? s.envColumns.data() : s.columns.data();
  const float* weights = env ? s.envWeights.data() : s.weights.data();
  const Index capacity = env ? n : 3 * n;
  PackedRows to = sink.target(env);
  if (d.writesFirst)
  {
    to.entryOffset = to.startOffset = base;
    packRows(columns, weights, capacity, counts, offsets, count, first, to, d.stream);
    return;
  }
  s.stageColumns.resize(std::max<Index>(nnz, 1));
  s.stageWeights.resize(std::max<Index>(nnz, 1));
  s.stageStarts.resize(count);
  s.stageCounts.resize(count);
  const PackedRows staged{ s.stageColumns.data(), s.stageWeights.data(), s.stageStarts.data(),
    s.stageCounts.data(), 0, base };
  packRows(columns, weights, capacity, counts, offsets, count, 0, staged, d.stream);
  const auto copy = [&](void* dst, const void* src, std::size_t bytes) {
    LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(dst, sink.device(), src, d.id, bytes, d.stream));
  };
  copy(to.columns + base, staged.columns, nnz * sizeof(Index));
  copy(to.weights + base, staged.weights, nnz * sizeof(float));
  copy(to.rowStarts + first, staged.rowStarts, count * sizeof(Index));
  copy(to.rowCounts + first, staged.rowCounts, count * sizeof(Index));
  d.sync(); // the staging buffers are reused by the next batch
}

/// Traces and compresses elements [first, first + count) on `d` into the sink.
void linkBatch(EngineDevice& d, const LinkJob& job, MatrixSink& sink, Index first, Index count)
{
  const Index n = job.params.trace.raysPerVertex;
  LinkScratch& s = d.scratch;
  s.hits.resize(std::size_t(count) * n);
  s.columns.resize(std::size_t(count) * 3 * n);
  s.weights.resize(std::size_t(count) * 3 * n);
  s.envColumns.resize(std::size_t(count) * n);
  s.envWeights.resize(std::size_t(count) * n);
  for (GPUBuffer<Index>* b : { &s.counts, &s.offsets, &s.envCounts, &s.envOffsets })
  {
    b->resize(count);
  }

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
  // Row offsets within the batch, and its entry totals in one read-back.
  exclusiveSum(s.counts.data(), s.offsets.data(), count, s.temp, d.stream);
  exclusiveSum(s.envCounts.data(), s.envOffsets.data(), count, s.temp, d.stream);
  const Index last = count - 1;
  const std::pair<Index*, const Index*> reads[] = { { d.totals + 0, s.offsets.data() + last },
    { d.totals + 1, s.counts.data() + last }, { d.totals + 2, s.envOffsets.data() + last },
    { d.totals + 3, s.envCounts.data() + last } };
  for (const auto& [to, from] : reads)
  {
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(to, from, sizeof(Index), cudaMemcpyDeviceToHost, d.stream));
  }
  d.sync();
  const Index nnz = d.totals[0] + d.totals[1], envNnz = d.totals[2] + d.totals[3];
  Index base = 0, envBase = 0;
  sink.reserve(nnz, envNnz, base, envBase);
  packInto(d, sink, false, n, first, count, base, nnz);
  packInto(d, sink, true, n, first, count, envBase, envNnz);
  LINKGI_CUDA_CHECK(cudaEventRecord(d.events[2], d.stream));
  d.sync();
  float trace = 0.f, compress = 0.f;
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&trace, d.events[0], d.events[1]));
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&compress, d.events[1], d.events[2]));
  d.msTrace += trace;
  d.msCompress += compress;
  // Elements cost differently in different parts of a scene, so one batch's speed is a
  // noisy estimate; averaging with the previous one keeps splits from oscillating.
  const double speed = count / std::max(1e-3, double(trace + compress));
  d.elementsPerMs = d.elementsPerMs > 0.0 ? 0.5 * (d.elementsPerMs + speed) : speed;
  d.linked += count;
  ++d.batches;
}
}

namespace
{
LinkJob makeJob(const Scene& s, const SolverOptions& options)
{
  LinkJob job;
  job.elements = Index(Elements{ s.vertexCount(), options.twoSided }.count());
  LinkTraceParams& t = job.params.trace;
  t.raysPerVertex = options.raysPerVertex;
  t.vertexCount = Index(s.vertexCount());
  t.twist = options.twist;
  t.seed = options.seed;
  t.eps = rayEpsilon(s);
  job.params.twoSided = options.twoSided;
  job.params.envWidth = s.environment.hasTexture() ? s.environment.width : 0;
  job.params.envHeight = s.environment.hasTexture() ? s.environment.height : 0;
  return job;
}

/// The matrices on the first device, at their worst-case size: every device appends its
/// rows there as its batches finish, so there is nothing to merge afterwards.
void reserveMatrices(EngineDevice& d0, Index elements, Index raysPerVertex)
{
  d0.use();
  for (DeviceCsr* m : { &d0.transport, &d0.environment })
  {
    const std::size_t perRow = m == &d0.transport ? 3 * raysPerVertex : raysPerVertex;
    m->columns.resize(std::size_t(elements) * perRow);
    m->weights.resize(std::size_t(elements) * perRow);
    m->rowStarts.resize(elements);
    m->rowCounts.resize(elements);
  }
}

/// One link stage over all devices: each sets itself up and runs batches until none are
/// left.
struct LinkStage
{
  const LinkJob& job;
  const std::vector<Vec3f>& directions;
  MatrixSink& sink;
  BatchScheduler& scheduler;
  const engine::StageContext& context;
  std::atomic<Index> done{ 0 };

  void run(EngineDevice& d, std::size_t i)
  {
    using clock = std::chrono::steady_clock;
    const auto began = clock::now();
    const Index n = job.params.trace.raysPerVertex;
    try
    {
      d.use();
      d.directions.upload(directions, d.stream);
      d.scratch.rawLinks.resize(1);
      d.scratch.rawLinks.fillZero(d.stream);
      d.msTrace = d.msCompress = 0.0;
      d.linked = 0;
      d.batches = 0;
      scheduler.limit(i, maxBatchFor(d, n));
      Index first = 0, count = 0;
      while (scheduler.next(i, first, count))
      {
        linkBatch(d, job, sink, first, count);
        done += count;
        // Only the caller's thread may ask: the callback may touch GUI state.
        if (i == 0)
        {
          context.check(double(done) / std::max<Index>(job.elements, 1));
        }
      }
      d.scratch.rawLinks.download(&d.rawLinks, 1);
    }
    catch (...)
    {
      scheduler.cancel();
      throw;
    }
    d.msWall = std::chrono::duration<double, std::milli>(clock::now() - began).count();
  }
};
}

void Engine::runOnAllDevices(const std::function<void(EngineDevice&, std::size_t)>& work)
{
  for (std::size_t i = 1; i < devices.size(); ++i)
  {
    EngineDevice& d = *devices[i];
    d.worker.start([&work, &d, i] { work(d, i); });
  }
  std::exception_ptr error;
  try
  {
    work(*devices[0], 0);
  }
  catch (...)
  {
    error = std::current_exception();
  }
  for (std::size_t i = 1; i < devices.size(); ++i)
  {
    try
    {
      devices[i]->worker.wait();
    }
    catch (...)
    {
      error = error ? error : std::current_exception();
    }
  }
  if (error)
  {
    std::rethrow_exception(error);
  }
}

void Engine::buildLinks(const engine::StageContext& c)
{
  const SolverOptions& options = c.options;
  const auto start = std::chrono::steady_clock::now();
  const LinkJob job = makeJob(c.scene, options);
  const Index ne = job.elements, n = options.raysPerVertex;
  const std::vector<Vec3f> dirs = makeDirectionSet(n);
  EngineDevice& d0 = *devices[0];
  reserveMatrices(d0, ne, n);
  MatrixSink sink(d0);
  std::vector<EngineDevice*> all;
  for (auto& d : devices)
  {
    all.push_back(d.get());
  }
  BatchScheduler scheduler(ne, all);
  LinkStage stage{ job, dirs, sink, scheduler, c };
  runOnAllDevices([&stage](EngineDevice& d, std::size_t i) { stage.run(d, i); });

  rawLinks = 0;
  double msCompress = 0.0;
  for (auto& d : devices)
  {
    rawLinks += d->rawLinks;
    msCompress = std::max(msCompress, d->msCompress);
  }
  d0.use();
  d0.transport.nonZeros = sink.used;
  d0.environment.nonZeros = sink.envUsed;
  rays = std::uint64_t(ne) * n;
  const double msAll = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  c.part("Compress", std::min(msCompress, msAll));
}
}
