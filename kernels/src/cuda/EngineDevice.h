// State of one GPU of the CUDA engine (private to CudaEngine.cpp and CudaLinks.cpp).
#pragma once

#include "CudaEngine.h"

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
  std::thread thread;
  std::mutex mutex;
  std::condition_variable changed;
  std::function<void()> job;
  std::exception_ptr error;
  bool pending = false, stop = false;
};

/// Scratch of one link batch on its device: hits, fixed-capacity rows and their counts.
struct LinkScratch
{
  GPUBuffer<LinkHit> hits;
  GPUBuffer<Index> columns, counts, offsets, envColumns, envCounts, envOffsets;
  GPUBuffer<float> weights, envWeights;
  GPUBuffer<unsigned long long> rawLinks;
  GPUBuffer<unsigned char> temp;
  // Packed rows of a device that cannot write into the first device's memory: copied there.
  GPUBuffer<Index> stageColumns, stageStarts, stageCounts;
  GPUBuffer<float> stageWeights;
  std::size_t bytes() const
  {
    return hits.bytes() + columns.bytes() + counts.bytes() + offsets.bytes() + envColumns.bytes() +
      envCounts.bytes() + envOffsets.bytes() + weights.bytes() + envWeights.bytes() + temp.bytes() +
      stageColumns.bytes() + stageStarts.bytes() + stageCounts.bytes() + stageWeights.bytes();
  }
};

struct EngineDevice
{
  int id = 0;
  cudaStream_t stream = nullptr;
  cudaEvent_t events[3] = {};
  Index* totals = nullptr; ///< pinned host memory: a batch's entry counts, read back at once
  bool writesFirst = true; ///< kernels here may store into the first device's memory

  // Geometry (every device).
  GPUBuffer<Vec3f> positions, normals, shifts, faceNormals, directions;
  GPUBuffer<Triangle> triangles;
  DeviceBvh bvh;
  double bvhBuildCost = 0.0; ///< DeviceBvh::cost() right after the last build

  // Links (every device).
  LinkScratch scratch;
  double elementsPerMs = 0.0; ///< speed of the last link batch, for the scheduler
  double msTrace = 0.0, msCompress = 0.0, msWall = 0.0;
  std::size_t linked = 0; ///< elements linked in the last link stage
  unsigned long long rawLinks = 0; ///< links before merging, last link stage
  std::uint32_t batches = 0;

  // First device only: topology, shading inputs, link matrices, light and bounce buffers.
  GPUBuffer<Index> neighbourOffsets, neighbours, edges, vertexEdges;
  GPUBuffer<Vec3f> albedo, emission, direct, output;
  GPUBuffer<float> vertexVisible, edgeVisible;
  GPUBuffer<Light> lights;
  GPUBuffer<unsigned long long> counter;
  DeviceCsr transport, environment;
  GPUBuffer<Rgba> texelRadiance, envIrradiance, fixedIrradiance, radiance[2], indirect;
  GPUBuffer<unsigned char> temp;

  DeviceWorker worker; ///< runs this device's link batches (devices after the first)

  explicit EngineDevice(int device);
  ~EngineDevice();
  void use() const { LINKGI_CUDA_CHECK(cudaSetDevice(id)); }
  void sync() const { LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream)); }
};
}
