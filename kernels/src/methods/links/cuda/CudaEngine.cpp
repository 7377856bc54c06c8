#include "cuda/DirectLightStage.h"
#include "methods/links/cuda/EngineDevice.h"

#include "cuda/Cuda.h"
#include "shared/Sampling.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <future>
#include <map>
#include <mutex>

namespace linkgi::cuda
{
namespace
{
using engine::msSince;

/// Lets kernels on `from` access `to`'s memory; once per process and pair (enabling it
/// twice is an error that compute-sanitizer reports).
bool enablePeerAccess(int from, int to)
{
  static std::mutex mutex;
  static std::map<std::pair<int, int>, bool> enabled;
  std::lock_guard<std::mutex> lock(mutex);
  const auto known = enabled.find({ from, to });
  if (known != enabled.end())
  {
    return known->second;
  }
  int can = 0;
  LINKGI_CUDA_CHECK(cudaDeviceCanAccessPeer(&can, from, to));
  bool ok = false;
  if (can)
  {
    LINKGI_CUDA_CHECK(cudaSetDevice(from));
    ok = cudaDeviceEnablePeerAccess(to, 0) == cudaSuccess;
    cudaGetLastError(); // a refusal only means staging copies
  }
  enabled[{ from, to }] = ok;
  return ok;
}

/// CudaBvhUpdate::Auto rebuilds a refit tree whose surface-area cost grew by this factor.
constexpr double kRebuildGrowth = 1.5;

}

DeviceWorker::DeviceWorker() : thread([this] { loop(); }) {}

DeviceWorker::~DeviceWorker()
{
  {
    std::lock_guard<std::mutex> lock(mutex);
    stop = true;
  }
  changed.notify_all();
  thread.join();
}

void DeviceWorker::start(std::function<void()> next)
{
  {
    std::lock_guard<std::mutex> lock(mutex);
    job = std::move(next);
    error = nullptr;
    pending = true;
  }
  changed.notify_all();
}

void DeviceWorker::wait()
{
  std::unique_lock<std::mutex> lock(mutex);
  changed.wait(lock, [this] { return !pending; });
  if (error)
  {
    std::rethrow_exception(error);
  }
}

void DeviceWorker::loop()
{
  std::unique_lock<std::mutex> lock(mutex);
  for (;;)
  {
    changed.wait(lock, [this] { return stop || pending; });
    if (stop)
    {
      return;
    }
    lock.unlock();
    std::exception_ptr failure;
    try
    {
      job();
    }
    catch (...)
    {
      failure = std::current_exception();
    }
    lock.lock();
    error = failure;
    pending = false;
    changed.notify_all();
  }
}

CsrView DeviceCsr::view(Index firstElement, int lanes) const
{
  CsrView v;
  v.rowStarts = rowStarts.data();
  v.rowCounts = rowCounts.data();
  v.columns = columns.data();
  v.weights = weights.data();
  v.rows = Index(rowStarts.size());
  v.firstElement = firstElement;
  v.nonZeros = nonZeros;
  v.lanes = lanes;
  return v;
}

EngineDevice::EngineDevice(int device) : id(device)
{
  use();
  LINKGI_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  for (cudaEvent_t& e : events)
  {
    LINKGI_CUDA_CHECK(cudaEventCreate(&e));
  }
  LINKGI_CUDA_CHECK(cudaEventCreateWithFlags(&ready, cudaEventDisableTiming));
  void* pinned = nullptr;
  LINKGI_CUDA_CHECK(cudaMallocHost(&pinned, 5 * sizeof(Offset)));
  totals = static_cast<Offset*>(pinned);
  tracedLightRays = reinterpret_cast<unsigned long long*>(totals + 4);
  *tracedLightRays = 0;
}

EngineDevice::~EngineDevice()
{
  cudaSetDevice(id);
  cudaFreeHost(totals);
  for (cudaEvent_t e : events)
  {
    cudaEventDestroy(e);
  }
  cudaEventDestroy(ready);
  cudaStreamDestroy(stream);
}

Engine::Engine(int maxDevices)
{
  std::string why;
  const std::vector<DeviceInfo> found = cuda::devices(&why);
  if (found.empty())
  {
    throw CudaError("The CUDA backend cannot run: " + why + ".", false);
  }
  const std::size_t use = maxDevices > 0 ? std::min<std::size_t>(found.size(), maxDevices) : found.size();
  std::size_t partitions = use;
  if (const char* p = std::getenv("LINKGI_CUDA_PARTITIONS"))
  {
    partitions = std::max<std::size_t>(use, std::strtoul(p, nullptr, 10));
  }
  for (std::size_t i = 0; i < partitions; ++i)
  {
    devices.push_back(std::make_unique<EngineDevice>(found[i % use].index));
  }
  meshTracer = cuda::traceThrough(devices[0]->bvh, devices[0]->id, devices[0]->stream);
  physicalDevices = int(use);
  identicalDevices = true;
  for (std::size_t i = 1; i < use; ++i)
  {
    identicalDevices = identicalDevices && found[i].name == found[0].name &&
      found[i].multiprocessors == found[0].multiprocessors;
  }
  name = (use > 1 ? std::to_string(use) + " x " : std::string()) + found[0].name;
  if (partitions > use)
  {
    name += " (" + std::to_string(partitions) + " partitions)";
  }
  // Peer access lets the bounce vectors' copies between GPUs go straight over NVLink; without
  // it cudaMemcpyPeerAsync stages them through the host.
  for (std::size_t a = 0; a < use; ++a)
  {
    for (std::size_t b = 0; b < use; ++b)
    {
      if (a != b)
      {
        enablePeerAccess(found[a].index, found[b].index);
      }
    }
  }
}

Engine::~Engine() = default;

int Engine::deviceCount() const
{
  return int(devices.size());
}

std::string Engine::description() const
{
  return name;
}

CsrView Engine::transport() const
{
  const EngineDevice& d0 = *devices[0];
  if (d0.blocks.size() != 1)
  {
    throw Error("The transport matrix is not one block on the first GPU.");
  }
  const DeviceCsr& w = d0.blocks[0].transport;
  return w.view(d0.blocks[0].first, lanesForRows(w.nonZeros, w.rowStarts.size()));
}

void Engine::linkProfile(SolverStats& stats) const
{
  stats.batchesPerDevice.clear();
  stats.msTracePerDevice.clear();
  stats.msCompressPerDevice.clear();
  stats.msWallPerDevice.clear();
  for (const auto& d : devices)
  {
    stats.batchesPerDevice.push_back(d->batches);
    stats.msTracePerDevice.push_back(d->msTrace);
    stats.msCompressPerDevice.push_back(d->msCompress);
    stats.msWallPerDevice.push_back(d->msWall);
  }
}

std::vector<std::size_t> Engine::linkedElements() const
{
  std::vector<std::size_t> out;
  for (const auto& d : devices)
  {
    std::size_t rows = 0;
    for (const MatrixBlock& b : d->blocks)
    {
      rows += b.transport.rowStarts.size();
    }
    out.push_back(rows);
  }
  return out;
}

void Engine::run(std::size_t stage, const engine::StageContext& c)
{
  if (c.options.raysPerVertex > kMaxCompressRays)
  {
    throw CudaError("the CUDA backend merges at most " + std::to_string(kMaxCompressRays) +
        " rays per vertex",
      false);
  }
  switch (stage)
  {
    case links::kGeometryStage:
      updateGeometry(c);
      break;
    case links::kLinkStage:
      buildLinks(c);
      break;
    case links::kLightLinkStage:
      computeDirectLight(c);
      break;
    case links::kBounceStage:
      bounceAndFinish(c);
      break;
  }
}

void Engine::describe(SolverStats& stats) const
{
  stats.backend = "cuda";
  stats.device = name;
  stats.devices = physicalDevices;
  const std::vector<std::size_t> linked = linkedElements();
  stats.linkedPerDevice.assign(linked.begin(), linked.end());
  linkProfile(stats);
  // What this engine's buffers held at most since the last update was described: the sum
  // over its GPUs of GPUBuffer allocations, not the devices' used memory.
  stats.gpuBytesAllocated = MemoryLedger::takePeak();
  stats.rays = rays;
  std::uint64_t compressed = 0, bytes = 0;
  for (const auto& d : devices)
  {
    for (const MatrixBlock& b : d->blocks)
    {
      compressed += b.transport.nonZeros;
      bytes += b.transport.usedBytes() + b.environment.usedBytes();
    }
  }
  stats.setCounter("LinksRaw", rawLinks);
  stats.setCounter("LinksCompressed", compressed);
  stats.setCounter("LinkBytes", bytes);
  stats.setCounter("DetailNodes", detail.nodes.size());
  stats.lightRays = *devices[0]->tracedLightRays; // the bounce stage has synchronized
}

void Engine::updateGeometry(const engine::StageContext& c)
{
  const Scene& s = c.scene;
  const SolverOptions& options = c.options;
  SolverStats& stats = c.stats;
  const Index nv = Index(s.vertexCount()), nt = Index(s.triangleCount());
  // What goes up: only the arrays that changed (a deformation moves positions, as a rule
  // not normals); what is derived from them on the GPU: after any of them changed.
  struct
  {
    bool topology, positions, normals, geometry;
  } const mask{ (c.changes & engine::kTopology) != 0, (c.changes & (engine::kTopology | engine::kPositions)) != 0,
    (c.changes & (engine::kTopology | engine::kNormals)) != 0 || devices[0]->normals.size() != s.normals.size(),
    (c.changes & engine::kGeometry) != 0 };
  if (mask.positions)
  {
    eps = rayEpsilon(s); // the ray origins' bound: once per geometry, not per light change
  }
  // The input goes up once, to the first partition, through pinned memory; the others copy
  // it from there (one host copy however many GPUs).
  const auto t = std::chrono::steady_clock::now();
  EngineDevice& d0 = *devices[0];
  d0.use();
  d0.staging.begin(PinnedStaging::room(s.triangles.size() * sizeof(Triangle)) +
    2 * PinnedStaging::room(s.positions.size() * sizeof(Vec3f)));
  if (mask.topology)
  {
    d0.staging.upload(d0.triangles, s.triangles, d0.stream);
  }
  if (mask.positions)
  {
    d0.staging.upload(d0.positions, s.positions, d0.stream);
  }
  if (mask.normals)
  {
    d0.staging.upload(d0.normals, s.normals, d0.stream);
  }
  LINKGI_CUDA_CHECK(cudaEventRecord(d0.ready, d0.stream));
  for (std::size_t i = 1; i < devices.size(); ++i)
  {
    EngineDevice& d = *devices[i];
    if (mask.topology)
    {
      copyFrom(d0, d, &EngineDevice::triangles);
    }
    if (mask.positions)
    {
      copyFrom(d0, d, &EngineDevice::positions);
    }
    if (mask.normals)
    {
      copyFrom(d0, d, &EngineDevice::normals);
    }
  }
  // The detail nodes on the host while the GPUs build their BVHs.
  std::future<DetailNodes> nextDetail;
  if (mask.geometry)
  {
    nextDetail = std::async(std::launch::async, [&s] { return detailNodes(s, detailNodeBudget(s.vertexCount())); });
  }
  HostBvh sah; // CudaBvhBuild::HostSah: built once, uploaded to every device
  std::once_flag sahBuilt;
  // Every partition's BVH at once, each from its own thread: a build waits for its GPU
  // between rounds, so building them in turn from one thread added the builds up.
  runOnAllDevices([&](EngineDevice& d, std::size_t i) {
    d.use();
    if (i == 0)
    {
      // What the link rays need besides the BVH, derived on the first GPU: no host
      // topology on the critical path (it took 5.6 ms of conference's update on 16 cores).
      if (mask.topology)
      {
        d.topology.build(d.triangles.data(), nt, nv, d.stream);
      }
      if (mask.geometry)
      {
        d.origins.resize(nv);
        d.faceNormals.resize(nt);
        rayOrigins(d.positions.data(), d.normals.data(), d.topology.neighbourOffsets.data(),
          d.topology.neighbours.data(), nv, eps, d.origins.data(), d.stream);
        frontFaceNormals(d.positions.data(), d.normals.data(), d.triangles.data(), nt, d.faceNormals.data(), d.stream);
      }
      c.part("Topology", msSince(t)); // the host's part: queueing uploads and kernels
    }
    bool rebuild = mask.topology || (mask.positions && options.cudaBvhUpdate == CudaBvhUpdate::Rebuild);
    if (!rebuild && mask.positions)
    {
      d.bvh.refit(d.positions.data(), d.triangles.data(), d.stream);
      // Auto: a refit tree whose boxes have swollen by half is rebuilt (one cost pass).
      rebuild = options.cudaBvhUpdate == CudaBvhUpdate::Auto && d.bvh.cost(d.stream) > kRebuildGrowth * d.bvhBuildCost;
    }
    if (rebuild && options.cudaBvhBuild == CudaBvhBuild::HostSah)
    {
      std::call_once(sahBuilt, [&] { sah.buildSah(s.positions, s.triangles); });
      d.bvh.upload(sah, d.positions.data(), d.triangles.data(), d.stream);
      d.bvhBuildCost = options.cudaBvhUpdate == CudaBvhUpdate::Auto ? d.bvh.cost(d.stream) : 0.0;
    }
    else if (rebuild)
    {
      d.bvh.build(d.positions.data(), nv, d.triangles.data(), nt, d.stream);
      d.bvhBuildCost = options.cudaBvhUpdate == CudaBvhUpdate::Auto ? d.bvh.cost(d.stream) : 0.0;
    }
    if (i == 0)
    {
      stats.builtBvh = rebuild;
      stats.refitBvh = !rebuild && mask.positions;
      stats.bvhBuilds += rebuild;
      stats.bvhRefits += stats.refitBvh;
    }
  });
  if (mask.geometry)
  {
    // Small next to the mesh: each partition takes its own copy from the host.
    detail = nextDetail.get();
    for (const auto& d : devices)
    {
      d->use();
      d->detailFirst.upload(detail.first, d->stream);
      d->detailSteps.upload(detail.steps, d->stream);
      d->detailNodes.upload(detail.nodes, d->stream);
    }
    d0.use();
  }
  if (mask.geometry && devices.size() > 1)
  {
    d0.use();
    LINKGI_CUDA_CHECK(cudaEventRecord(d0.ready, d0.stream));
    for (std::size_t i = 1; i < devices.size(); ++i)
    {
      copyFrom(d0, *devices[i], &EngineDevice::origins);
      copyFrom(d0, *devices[i], &EngineDevice::faceNormals);
    }
  }
  for (const auto& d : devices)
  {
    d->sync();
  }
  edgeCount = d0.topology.edgeCount();
}

DetailParams Engine::detailParams(const EngineDevice& d, bool twoSided) const
{
  DetailParams p;
  p.bvh = d.bvh.view();
  p.triangles = d.triangles.data();
  p.positions = d.positions.data();
  p.normals = d.normals.data();
  p.faceNormals = d.faceNormals.data();
  p.origins = d.origins.data();
  p.nodes = d.detailNodes.data();
  p.nodeCount = Index(detail.nodes.size());
  p.sides = twoSided ? 2 : 1;
  return p;
}

void Engine::computeDirectLight(const engine::StageContext& c)
{
  EngineDevice& d = *devices[0];
  d.use();
  queueDirectLight(c.scene, c.options, { d.bvh, d.positions, d.normals, d.origins, d.topology, edgeCount },
    { d.lights, d.vertexVisible, d.edgeVisible, d.direct, d.counter }, d.stream);
  d.nodeDirect.resize(detail.columns(c.options.twoSided));
  detailDirect(detailParams(d, c.options.twoSided), d.lights.data(), Index(d.lights.size()), d.nodeDirect.data(),
    d.counter.data(), d.stream);
  // No wait here: the bounces queue behind the light links, the ray count arrives with
  // their outputs, and the other partitions copy E_d after this event.
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(d.tracedLightRays, d.counter.data(), sizeof(unsigned long long),
    cudaMemcpyDeviceToHost, d.stream));
  LINKGI_CUDA_CHECK(cudaEventRecord(d.ready, d.stream));
}
}
