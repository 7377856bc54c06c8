// State of one GPU of the CUDA engine (private to CudaEngine.cpp and CudaLinks.cpp).
#pragma once

#include "methods/links/cuda/CudaEngine.h"
#include "cuda/DeviceTopology.h"
#include "cuda/PinnedStaging.h"

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace linkgi::cuda
{
/// A thread that stays with one device, so the link stage starts its batches on every GPU
/// at once without creating threads (~0.1 ms each, on the critical path).
class DeviceWorker
{
public:
  DeviceWorker();
  ~DeviceWorker();
  DeviceWorker(const DeviceWorker&) = delete;
  DeviceWorker& operator=(const DeviceWorker&) = delete;
  /// Runs job() on the worker; wait() returns when it is done (rethrowing its exception).
  void start(std::function<void()> job);
  void wait();

private:
  void loop();
  std::mutex mutex;
  std::condition_variable changed;
  std::function<void()> job;
  std::exception_ptr error;
  bool pending = false, stop = false;
  std::thread thread; ///< last: it starts in the constructor and uses every member above
};

/// Scratch of one link batch on its device: hits, fixed-capacity rows and their counts.
struct LinkScratch
{
  GPUBuffer<LinkHit> hits;
  GPUBuffer<Index> columns, counts, envColumns, envCounts;
  GPUBuffer<Offset> offsets, envOffsets;
  GPUBuffer<float> weights, envWeights;
  GPUBuffer<unsigned long long> rawLinks;
  GPUBuffer<unsigned char> temp;
  std::size_t bytes() const
  {
    return hits.bytes() + columns.bytes() + counts.bytes() + offsets.bytes() + envColumns.bytes() +
      envCounts.bytes() + envOffsets.bytes() + weights.bytes() + envWeights.bytes() + temp.bytes();
  }
};

/// The rows of one link batch, W and Wenv, on the partition that linked them.
struct MatrixBlock
{
  DeviceCsr transport, environment;
  Index first = 0, count = 0; ///< elements [first, first + count)
};

/// One partition of the engine: a GPU, or a share of one (LINKGI_CUDA_PARTITIONS), with its
/// own stream, worker thread, geometry, BVH, link rows and bounce vectors. It links batches
/// of elements, keeps their rows, and computes those rows of every bounce; the first
/// partition also holds the topology, the light links and the output.
struct EngineDevice
{
  int id = 0;
  cudaStream_t stream = nullptr;
  cudaEvent_t events[3] = {};
  cudaEvent_t ready = nullptr; ///< recorded before other partitions copy from this one
  Offset* totals = nullptr; ///< pinned host memory: a batch's entry counts, read back at once
  /// Pinned, beside `totals`: the last light-link stage's shadow rays, read back with the
  /// bounces' outputs (the light links queue their work without waiting for it).
  unsigned long long* tracedLightRays = nullptr;

  // Geometry (every partition).
  GPUBuffer<Vec3f> positions, normals, faceNormals, directions;
  GPUBuffer<RayOrigin> origins;
  GPUBuffer<Triangle> triangles;
  GPUBuffer<Index> detailFirst;          ///< DetailNodes::first
  GPUBuffer<std::uint16_t> detailSteps;  ///< DetailNodes::steps
  GPUBuffer<DetailNode> detailNodes;     ///< DetailNodes::nodes
  DeviceBvh bvh;
  double bvhBuildCost = 0.0; ///< DeviceBvh::cost() right after the last build

  // Links (every partition): scratch, and this partition's rows, one block per batch.
  LinkScratch scratch;
  std::vector<MatrixBlock> blocks;
  std::size_t blocksUsed = 0; ///< during the link stage: blocks written so far
  double elementsPerMs = 0.0; ///< speed of the last link batch, for the scheduler
  double msTrace = 0.0, msCompress = 0.0, msWall = 0.0;
  std::size_t linked = 0; ///< elements linked in the last link stage
  std::vector<BatchCost> batchCosts; ///< the last link stage's batches on this partition
  unsigned long long rawLinks = 0; ///< links before merging, last link stage
  std::uint32_t batches = 0;

  // Bounces (every partition: whole vectors, of which it computes its rows).
  GPUBuffer<Vec3f> albedo, emission, direct;
  GPUBuffer<Vec3f> nodeDirect; ///< E_d at the detail nodes (both sides when two-sided)
  GPUBuffer<Rgba> texelRadiance, envIrradiance, fixedIrradiance, radiance[2], indirect;

  PinnedStaging staging; ///< this partition's uploads and downloads

  // First partition only: topology, light links and the output.
  DeviceTopology topology;
  GPUBuffer<Vec3f> output;
  GPUBuffer<float> vertexVisible, edgeVisible;
  GPUBuffer<Light> lights;
  GPUBuffer<unsigned long long> counter;

  DeviceWorker worker; ///< runs this partition's link batches (partitions after the first)

  explicit EngineDevice(int device);
  ~EngineDevice();
  void use() const { LINKGI_CUDA_CHECK(cudaSetDevice(id)); }
  void sync() const { LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream)); }
};

/// Makes `to`'s copy of a buffer equal to `from`'s: resized, then copied on to's stream once
/// the work `from` queued before its last `ready` record is done (over NVLink where peer
/// access is on). Inputs go up once, to the first partition, and reach the others this way.
template <typename T>
void copyFrom(const EngineDevice& from, EngineDevice& to, GPUBuffer<T> EngineDevice::*buffer)
{
  const GPUBuffer<T>& source = from.*buffer;
  GPUBuffer<T>& target = to.*buffer;
  to.use();
  target.resize(source.size());
  if (source.size())
  {
    LINKGI_CUDA_CHECK(cudaStreamWaitEvent(to.stream, from.ready, 0));
    LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(target.data(), to.id, source.data(), from.id,
      source.size() * sizeof(T), to.stream));
  }
}
}
