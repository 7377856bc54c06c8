// What a method's backend on one GPU shares (instant radiosity's and photon mapping's): the
// device, its stream and pinned counters; the mesh (arrays, topology, ray-origin shifts,
// face normals, BVH), uploaded through pinned memory as it changes; the direct-light stage's
// buffers; and the finish, which turns E_d and E_ind into the solution with one wait.
#pragma once

#include "cuda/DeviceBvh.h"
#include "cuda/DeviceTopology.h"
#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"
#include "cuda/PinnedStaging.h"

#include "engine/Pipeline.h"
#include "shared/RayOrigin.h"

#include <initializer_list>
#include <string>

namespace linkgi::cuda
{
/// The mesh on the GPU: arrays, topology, ray origins, face normals and BVH.
struct DeviceMesh
{
  GPUBuffer<Vec3f> positions, normals, faceNormals;
  GPUBuffer<RayOrigin> origins;
  GPUBuffer<Triangle> triangles;
  DeviceTopology topology;
  DeviceBvh bvh;
  Index vertexCount = 0, triangleCount = 0;
  SceneExtent extent; ///< of the positions uploaded
  PinnedStaging staging;

  /// Uploads what `changes` touched (through pinned memory) and queues the rest on `stream`
  /// (no wait). The previous update's copies must have completed.
  void update(const Scene& s, engine::Changes changes, cudaStream_t stream, SolverStats* stats);
};

/// Makes the first CUDA device current and returns its number; CudaError without one.
int useFirstDevice();

/// A backend's GPU (the first), its stream and `slots` counters in pinned host memory.
class DeviceContext
{
public:
  explicit DeviceContext(int slots);
  ~DeviceContext();
  DeviceContext(const DeviceContext&) = delete;
  DeviceContext& operator=(const DeviceContext&) = delete;

  /// What every one-GPU backend reports: backend, device, one device, the peak of the
  /// engine's allocations; no per-device link figures.
  void describe(SolverStats& st) const;

  int device = 0; ///< its number
  cudaStream_t stream = nullptr;
  std::string name;
  unsigned long long* counters = nullptr; ///< pinned: read them after a wait
};

/// The direct-light stage's buffers (DirectLightStage.h), kept between updates.
struct DeviceDirectLight
{
  GPUBuffer<Light> lights;
  GPUBuffer<float> vertexVisible, edgeVisible;
  GPUBuffer<Vec3f> direct; ///< E_d per element
  GPUBuffer<unsigned long long> counter;

  /// Queues E_d on `mesh`, and the copy of its shadow-ray count to `pinnedCount` (read it
  /// after the next wait). No wait.
  void queue(const Scene& scene, const SolverOptions& options, const DeviceMesh& mesh,
    unsigned long long* pinnedCount, cudaStream_t stream);
};

/// The end of an update on one GPU: smoothing and outgoing radiance (cuda::finish) from E_d
/// and all of E_ind, downloaded into the solution with the update's one wait.
struct DeviceFinish
{
  GPUBuffer<Vec3f> output;
  PinnedStaging staging;

  /// Another device array downloaded beside the solution: `bytes` of `from` into `to`.
  struct Extra
  {
    const void* from;
    std::size_t bytes;
    void* to;
  };

  /// sol.direct, sol.indirect and sol.radiance per element from `direct` and `indirect`
  /// (albedo, emission: device, emission null without emissive surfaces), and `extras`.
  /// Waits for the stream.
  void run(const Scene& scene, const SolverOptions& options, const DeviceMesh& mesh, const Vec3f* direct,
    const Rgba* indirect, const Vec3f* albedo, const Vec3f* emission, Solution& sol,
    std::initializer_list<Extra> extras, cudaStream_t stream);
};
}
