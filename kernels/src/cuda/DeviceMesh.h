// The mesh on one GPU as instant radiosity and photon mapping keep it: arrays, topology,
// ray-origin shifts, face normals and BVH, uploaded through pinned memory as they change.
#pragma once

#include "cuda/DeviceBvh.h"
#include "cuda/DeviceTopology.h"
#include "cuda/GPUBuffer.h"
#include "cuda/PinnedStaging.h"

#include "engine/Pipeline.h"
#include "ir/IrHost.h"

namespace linkgi::cuda
{
/// The mesh on the GPU: arrays, topology, shifts, face normals and BVH.
struct DeviceMesh
{
  GPUBuffer<Vec3f> positions, normals, shifts, faceNormals;
  GPUBuffer<Triangle> triangles;
  DeviceTopology topology;
  DeviceBvh bvh;
  Index vertexCount = 0, triangleCount = 0;
  ir::SceneExtent extent; ///< of the positions uploaded
  PinnedStaging staging;

  /// Uploads what `changes` touched (through pinned memory) and queues the rest on `stream`
  /// (no wait). The previous update's copies must have completed.
  void update(const Scene& s, engine::Changes changes, cudaStream_t stream, SolverStats* stats);
};

/// Makes the first CUDA device current and returns its number; CudaError without one.
int useFirstDevice();
}
