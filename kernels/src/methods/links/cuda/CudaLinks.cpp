// The link stage of the CUDA engine: the element range in batches across all partitions
// (GPUs), each batch sized by its partition's speed on its previous batch (paper, sec. 3.2),
// traced and compressed where it was traced, and its rows kept there as one block: no merge
// pass, no rows crossing between GPUs, and the matrix's memory adds up over the GPUs.
#include "methods/links/cuda/EngineDevice.h"
#include "cuda/Primitives.h"

#include "shared/Sampling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <mutex>

namespace linkgi::cuda
{
namespace
{
/// Hands out element ranges. With a plan (identical GPUs), each device takes its own
/// contiguous range, in batches its memory holds. Without one, a device's batch takes about
/// `targetMs` at its last measured speed; once what is left would not fill one more round,
/// the rest is split in proportion to the speeds so all devices finish together.
class BatchScheduler
{
public:
  /// `plan`: boundaries of one contiguous range per device (equalCostSplit), or empty for
  /// batches sized by the devices' speeds.
  BatchScheduler(Index total, std::vector<EngineDevice*> devices, std::vector<Index> plan)
    : total(total), devices(std::move(devices)), maxBatch(this->devices.size(), total), plan(std::move(plan))
  {
    if (!this->plan.empty())
    {
      planned.assign(this->plan.begin(), this->plan.end() - 1);
    }
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
    if (!plan.empty())
    {
      // The device's own range, in batches its memory holds.
      const Index end = plan[device + 1];
      if (planned[device] >= end || stop)
      {
        return false;
      }
      first = planned[device];
      count = std::min(end - first, maxBatch[device]);
      planned[device] += count;
      return true;
    }
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
  std::vector<Index> plan, planned; ///< boundaries, and each device's next element in its range
  bool stop = false;
};

struct LinkJob
{
  LinkCompressParams params;
  Index elements = 0;
  Index detailNodes = 0; ///< per side
};

/// Largest batch whose scratch fits in about half of the device's free memory; at most
/// LINKGI_CUDA_MAX_BATCH elements where that is set (a testing knob: several batches, and
/// so several blocks of rows, per partition on a small scene).
Index maxBatchFor(const EngineDevice& d, Index raysPerVertex)
{
  std::size_t freeBytes = 0, totalBytes = 0;
  LINKGI_CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes));
  const std::size_t perElement = std::size_t(raysPerVertex) *
      (sizeof(LinkHit) + 4 * (sizeof(Index) + sizeof(float))) + 64;
  std::size_t most = std::max<std::size_t>(256, (freeBytes + d.scratch.bytes()) / 2 / perElement);
  if (const char* knob = std::getenv("LINKGI_CUDA_MAX_BATCH"))
  {
    most = std::min<std::size_t>(most, std::max<std::size_t>(1, std::strtoull(knob, nullptr, 10)));
  }
  return Index(std::min<std::size_t>(kInvalidIndex - 1, most));
}

/// Packs a batch's rows of W (or Wenv) from the fixed-capacity scratch into its block.
void packInto(EngineDevice& d, DeviceCsr& m, bool env, Index n, Index count, Offset nnz)
{
  LinkScratch& s = d.scratch;
  m.rowStarts.resize(count);
  m.rowCounts.resize(count);
  m.columns.resize(std::max<Offset>(nnz, 1));
  m.weights.resize(std::max<Offset>(nnz, 1));
  m.nonZeros = nnz;
  const PackedRows to{ m.columns.data(), m.weights.data(), m.rowStarts.data(), m.rowCounts.data() };
  packRows(env ? s.envColumns.data() : s.columns.data(), env ? s.envWeights.data() : s.weights.data(),
    env ? n : 3 * n, env ? s.envCounts.data() : s.counts.data(),
    env ? s.envOffsets.data() : s.offsets.data(), count, to, d.stream);
}

/// Traces and compresses elements [first, first + count) on `d` into a new block of its rows.
void linkBatch(EngineDevice& d, const LinkJob& job, Index first, Index count)
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
  s.envOffsets.resize(count);

  LinkCompressParams p = job.params;
  p.trace.bvh = d.bvh.view();
  p.trace.positions = d.positions.data();
  p.trace.normals = d.normals.data();
  p.trace.origins = d.origins.data();
  p.trace.directions = d.directions.data();
  p.trace.firstElement = first;
  p.trace.elementCount = count;
  p.triangles = d.triangles.data();
  p.faceNormals = d.faceNormals.data();
  if (job.detailNodes)
  {
    p.detail = DetailGrid{ d.detailFirst.data(), d.detailSteps.data(), job.elements, job.detailNodes };
  }

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
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(d.totals + 0, s.offsets.data() + last, sizeof(Offset), cudaMemcpyDeviceToHost, d.stream));
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(d.totals + 2, s.envOffsets.data() + last, sizeof(Offset), cudaMemcpyDeviceToHost, d.stream));
  Index* lastCounts = reinterpret_cast<Index*>(d.totals + 1); // pinned, as the totals
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(lastCounts, s.counts.data() + last, sizeof(Index), cudaMemcpyDeviceToHost, d.stream));
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(lastCounts + 1, s.envCounts.data() + last, sizeof(Index), cudaMemcpyDeviceToHost, d.stream));
  d.sync();
  const Offset nnz = d.totals[0] + lastCounts[0], envNnz = d.totals[2] + lastCounts[1];
  // The batch's rows stay on this partition, as one block of its matrices.
  // A block of the last link stage is reused: same batches, no allocation.
  if (d.blocksUsed == d.blocks.size())
  {
    d.blocks.emplace_back();
  }
  MatrixBlock& block = d.blocks[d.blocksUsed++];
  block.first = first;
  block.count = count;
  packInto(d, block.transport, false, n, count, nnz);
  packInto(d, block.environment, true, n, count, envNnz);
  LINKGI_CUDA_CHECK(cudaEventRecord(d.events[2], d.stream));
  d.sync();
  float trace = 0.f, compress = 0.f;
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&trace, d.events[0], d.events[1]));
  LINKGI_CUDA_CHECK(cudaEventElapsedTime(&compress, d.events[1], d.events[2]));
  d.msTrace += trace;
  d.msCompress += compress;
  // The split of the next relink weighs elements by their trace time alone: the kernels'
  // own time, whereas the time up to the packing also holds the host's allocations when a
  // batch outgrew its block (which would make the grown range look costly, and shrink it).
  d.batchCosts.push_back({ first, count, double(trace) });
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
LinkJob makeJob(const Scene& s, const SolverOptions& options, const DetailNodes& detail)
{
  const std::size_t elements = Elements{ s.vertexCount(), options.twoSided }.count();
  if (elements + detail.columns(options.twoSided) >= kInvalidIndex)
  {
    throw Error("The CUDA backend links at most " + std::to_string(kInvalidIndex - 1) +
      " elements and detail nodes (vertices, twice that for two-sided); got " +
      std::to_string(elements + detail.columns(options.twoSided)) + ".");
  }
  LinkJob job;
  job.elements = Index(elements);
  job.detailNodes = Index(detail.nodes.size());
  LinkTraceParams& t = job.params.trace;
  t.raysPerVertex = options.raysPerVertex;
  t.vertexCount = Index(s.vertexCount());
  t.twist = options.twist;
  t.seed = options.seed;
  job.params.twoSided = options.twoSided;
  job.params.envWidth = s.environment.hasTexture() ? s.environment.width : 0;
  job.params.envHeight = s.environment.hasTexture() ? s.environment.height : 0;
  return job;
}

/// One link stage over all devices: each sets itself up and runs batches until none are
/// left.
struct LinkStage
{
  const LinkJob& job;
  const std::vector<Vec3f>& directions;
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
      d.batchCosts.clear();
      d.blocksUsed = 0;
      scheduler.limit(i, maxBatchFor(d, n));
      Index first = 0, count = 0;
      while (scheduler.next(i, first, count))
      {
        linkBatch(d, job, first, count);
        done += count;
        // Only the caller's thread may ask: the callback may touch GUI state.
        if (i == 0)
        {
          context.check(double(done) / std::max<Index>(job.elements, 1));
        }
      }
      d.scratch.rawLinks.download(&d.rawLinks, 1);
      d.blocks.resize(d.blocksUsed); // blocks of a last stage with more batches
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

std::vector<Index> equalCostSplit(std::vector<BatchCost> last, Index elements, std::size_t parts)
{
  std::sort(last.begin(), last.end(), [](const BatchCost& a, const BatchCost& b) { return a.first < b.first; });
  double total = 0.0;
  Index covered = 0;
  for (const BatchCost& b : last)
  {
    if (b.first != covered || b.count == 0 || !(b.ms > 0.0))
    {
      return {};
    }
    covered += b.count;
    total += b.ms;
  }
  if (covered != elements || parts < 2 || elements < parts)
  {
    return {};
  }
  std::vector<Index> bounds{ 0 };
  double before = 0.0; // the cost of the batches before `b`
  std::size_t b = 0;
  for (std::size_t k = 1; k < parts; ++k)
  {
    const double target = total * double(k) / double(parts);
    while (b + 1 < last.size() && before + last[b].ms < target)
    {
      before += last[b++].ms;
    }
    const double within = std::clamp((target - before) / last[b].ms, 0.0, 1.0);
    const Index at = last[b].first + Index(std::llround(within * last[b].count));
    bounds.push_back(std::clamp(at, Index(bounds.back() + 1), Index(elements - (parts - k))));
  }
  bounds.push_back(elements);
  return bounds;
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
  const LinkJob job = makeJob(c.scene, options, detail);
  const Index ne = job.elements, n = options.raysPerVertex;
  const std::vector<Vec3f> dirs = makeDirectionSet(n);
  std::vector<EngineDevice*> all;
  for (auto& d : devices)
  {
    all.push_back(d.get());
  }
  // Identical GPUs take one contiguous range each: of equal cost by the last link stage
  // (elements cost differently in different parts of a scene), or of equal size when there
  // is none. GPUs of different kinds take batches sized by each one's measured speed.
  std::vector<Index> plan;
  if (identicalDevices && devices.size() > 1 && ne >= devices.size())
  {
    plan = equalCostSplit(lastBatches, ne, devices.size());
    if (plan.empty())
    {
      plan = equalCostSplit({ { 0, ne, 1.0 } }, ne, devices.size());
    }
  }
  BatchScheduler scheduler(ne, all, plan);
  LinkStage stage{ job, dirs, scheduler, c };
  lastBatches.clear();
  runOnAllDevices([&stage](EngineDevice& d, std::size_t i) { stage.run(d, i); });
  for (auto& d : devices)
  {
    lastBatches.insert(lastBatches.end(), d->batchCosts.begin(), d->batchCosts.end());
  }

  rawLinks = 0;
  double msCompress = 0.0;
  for (auto& d : devices)
  {
    rawLinks += d->rawLinks;
    msCompress = std::max(msCompress, d->msCompress);
  }
  rays = std::uint64_t(ne) * n;
  const double msAll = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  c.part("Compress", std::min(msCompress, msAll));
}
}
