// Launchers of the light paths' CUDA kernels (shared/LightPaths.h on the GPU): host-callable,
// no __global__ here. Instant radiosity's VPLs and photon mapping's photons are their hits.
#pragma once

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"
#include "cuda/OneDevice.h"
#include "engine/Pipeline.h"
#include "shared/LightPaths.h"

namespace linkgi::paths::gpu
{
/// Light path p of scene.paths (device pointers in `scene`) into slots[p (bounces + 1), ...),
/// its VPL count into counts[p]: one thread per path.
void traceLightPaths(const PathScene& scene, const BvhView& bvh, Vpl* slots, Index* counts,
  cudaStream_t stream);

/// What light paths read on the device besides the mesh: the source table, the lights, the
/// materials and the sky, uploaded as they change.
struct DevicePathScene
{
  cuda::GPUBuffer<Source> sources;
  cuda::GPUBuffer<float> cdf;
  cuda::GPUBuffer<Light> lights;
  cuda::GPUBuffer<Vec3f> albedo, emission, envTexels;
  cuda::GPUBuffer<std::uint8_t> materials; ///< with `specular` only
  cuda::GPUBuffer<float> ior;
  bool specular = false; ///< mirrors and glass are passed (photon mapping), not lit as diffuse

  /// Uploads `setup`'s sources and the lights, and what `changes` touched of the albedo,
  /// the materials (when `passSpecular` and the scene has mirrors or glass), the emission and
  /// the sky; returns setup.view over the device's arrays and `mesh`. No wait.
  PathScene upload(const Scene& scene, const PathSetup& setup, engine::Changes changes, const cuda::DeviceMesh& mesh,
    bool passSpecular, cudaStream_t stream);
};

/// Light paths' hits on the device: bounces + 1 slots per path, the count each used, and
/// their exclusive sum.
struct DevicePaths
{
  cuda::GPUBuffer<Vpl> slots;
  cuda::GPUBuffer<Index> counts;
  cuda::GPUBuffer<Offset> pathOffsets;
  cuda::GPUBuffer<unsigned char> scanTemp;
};

/// Traces view.paths light paths into `paths`, then, where they left fewer than half of
/// `targetVpls` VPLs, the second pass the CPU's traceVplsCpu traces (secondPassPaths), which
/// replaces the first: view.paths becomes the pass kept. Waits once per pass to learn the
/// VPLs found (through `pinnedFound`, one slot of pinned host memory) and returns them.
std::size_t traceAllPaths(PathScene& view, const BvhView& bvh, std::uint32_t targetVpls, DevicePaths& paths,
  unsigned long long* pinnedFound, cudaStream_t stream);

/// The VPL set on the device as packVpls (shared/LightPaths.h) packs it on the host: the paths' VPLs in
/// path order, subset r the paths [subsetFirstPath(r), subsetFirstPath(r + 1)).
/// pathOffsets: the exclusive sum of counts over paths + 1 entries. vpls holds the total;
/// subsetOffsets subsets + 1 entries, subsetScale subsets.
void packVpls(const Vpl* slots, const Index* counts, const Offset* pathOffsets, std::uint32_t paths,
  std::uint32_t slotsPerPath, std::uint32_t subsets, Vpl* vpls, std::uint32_t* subsetOffsets,
  float* subsetScale, cudaStream_t stream);
}
