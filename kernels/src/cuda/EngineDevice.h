// State of one GPU of the CUDA engine (private to CudaEngine.cpp and CudaLinks.cpp).
#pragma once

#include "CudaEngine.h"

namespace linkgi::cuda
{
/// Rows [first, first + count) of W and Wenv, compressed on one device: their row counts
/// and entries sit in that device's LinkArena at the given bases.
struct LinkPiece
{
  Index first = 0, count = 0;
  int device = 0; ///< index into the engine's devices
  std::size_t rowBase = 0, base = 0, envBase = 0;
  Index nonZeros = 0, envNonZeros = 0;
};

/// The compressed rows of all batches a device ran, appended batch after batch. Buffers
/// only grow, so steady-state updates allocate nothing.
struct LinkArena
{
  GPUBuffer<Index> counts, columns, envCounts, envColumns;
  GPUBuffer<float> weights, envWeights;
  void clear()
  {
    for (GPUBuffer<Index>* b : { &counts, &columns, &envCounts, &envColumns })
    {
      b->growKeep(0, nullptr);
    }
    weights.growKeep(0, nullptr);
    envWeights.growKeep(0, nullptr);
  }
};

/// Scratch of one link batch: hits and fixed-capacity rows.
struct LinkScratch
{
  GPUBuffer<LinkHit> hits;
  GPUBuffer<Index> columns, counts, envColumns, envCounts, offsets;
  GPUBuffer<float> weights, envWeights;
  GPUBuffer<unsigned long long> rawLinks;
  GPUBuffer<unsigned char> temp;
  std::size_t bytes() const
  {
    return hits.bytes() + columns.bytes() + counts.bytes() + envColumns.bytes() +
      envCounts.bytes() + offsets.bytes() + weights.bytes() + envWeights.bytes() + temp.bytes();
  }
};

struct EngineDevice
{
  int id = 0;
  cudaStream_t stream = nullptr;
  cudaEvent_t events[3] = {};

  // Geometry (every device).
  GPUBuffer<Vec3f> positions, normals, shifts, faceNormals, directions;
  GPUBuffer<Triangle> triangles;
  DeviceBvh bvh;
  double bvhBuildCost = 0.0; ///< DeviceBvh::cost() right after the last build

  // Links (every device).
  LinkScratch scratch;
  LinkArena arena;
  std::vector<LinkPiece> pieces;
  double elementsPerMs = 0.0; ///< speed of the last link batch, for the scheduler
  double msTrace = 0.0, msCompress = 0.0;

  // First device only: topology, shading inputs, link matrices, light and bounce buffers.
  GPUBuffer<Index> neighbourOffsets, neighbours, edges, vertexEdges;
  GPUBuffer<Vec3f> albedo, emission, direct, output;
  GPUBuffer<float> vertexVisible, edgeVisible;
  GPUBuffer<Light> lights;
  GPUBuffer<unsigned long long> counter;
  GPUBuffer<Index> rowCounts;
  DeviceCsr transport, environment;
  GPUBuffer<Rgba> texelRadiance, envIrradiance, fixedIrradiance, radiance[2], indirect;
  GPUBuffer<unsigned char> temp;

  explicit EngineDevice(int device);
  ~EngineDevice();
  void use() const { LINKGI_CUDA_CHECK(cudaSetDevice(id)); }
  void sync() const { LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream)); }
};
}
