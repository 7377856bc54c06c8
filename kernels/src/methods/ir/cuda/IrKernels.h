// Launchers of instant radiosity's CUDA kernels: host-callable, no __global__ here. The
// per-item math is IrMath.h's, the same the CPU runs; traversal is linkgi/Bvh.h's.
#pragma once

#include "methods/ir/IrHost.h"
#include "methods/ir/IrMath.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"
#include "cuda/OneDevice.h"

namespace linkgi::ir::gpu
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

/// The VPL set on the device as packVpls (IrHost.h) packs it on the host: the paths' VPLs in
/// path order, subset r the paths [subsetFirstPath(r), subsetFirstPath(r + 1)).
/// pathOffsets: the exclusive sum of counts over paths + 1 entries. vpls holds the total;
/// subsetOffsets subsets + 1 entries, subsetScale subsets.
void packVpls(const Vpl* slots, const Index* counts, const Offset* pathOffsets, std::uint32_t paths,
  std::uint32_t slotsPerPath, std::uint32_t subsets, Vpl* vpls, std::uint32_t* subsetOffsets,
  float* subsetScale, cudaStream_t stream);

/// buildProxy (IrHost.h) on the device: the same clusters at the same means (summed in
/// vertex order), the same set of triangles, numbered in cell order instead of first
/// appearance. Scratch is kept for the next build.
class DeviceProxy
{
public:
  /// Whether the GPU can build this grid over `vertexCount` vertices (three cluster numbers
  /// of a triangle must fit one 64-bit sort key); buildProxy on the host otherwise.
  static bool fits(const ProxyGrid& grid, std::size_t vertexCount);
  /// Clusters the device mesh; synchronizes once to learn the proxy's sizes.
  void build(const ProxyGrid& grid, const Vec3f* positions, Index vertexCount,
    const Triangle* triangles, Index triangleCount, cudaStream_t stream);
  cuda::GPUBuffer<Vec3f> positions;   ///< positionCount used
  cuda::GPUBuffer<Triangle> triangles; ///< triangleCount used
  Index positionCount = 0, triangleCount = 0;

private:
  cuda::GPUBuffer<std::uint64_t> keys, sortedKeys;
  cuda::GPUBuffer<Index> ids, order, heads, cluster, first;
  cuda::GPUBuffer<Offset> scanned, sizes;
  cuda::GPUBuffer<unsigned char> temp;
};

/// What the gather reads on the device.
struct GatherLaunch
{
  BvhView visibility; ///< the mesh, or the proxy; no triangles = everything visible
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const RayOrigin* origins = nullptr;
  Index vertexCount = 0;
  bool twoSided = false;
  const Vpl* vpls = nullptr;
  const std::uint32_t* subsetOffsets = nullptr; ///< subsets + 1
  const float* subsetScale = nullptr;
  GatherParams params; ///< params.subsets: the number of subsets
  /// Thread i gathers element order[i] (elementsBySubset), so that a warp's threads walk the
  /// same VPLs in step; nullptr: element i.
  const Index* order = nullptr;
};

/// The elements (both sides when twoSided) sorted by their VPL subset (vertexSubset), in
/// element order within a subset, into `order`; `keys`, `ids` and `temp` are scratch.
void elementsBySubset(Index vertexCount, bool twoSided, std::uint32_t subsets, std::uint32_t seed,
  cuda::GPUBuffer<std::uint64_t>& keys, cuda::GPUBuffer<Index>& ids, cuda::GPUBuffer<unsigned char>& temp,
  cuda::GPUBuffer<Index>& order, cudaStream_t stream);
/// out[e] = E_ind of element e from its VPL subset (gatherCpu's sum, same order); `rays`
/// adds the shadow rays traced. One thread per element.
void gatherVpls(const GatherLaunch& p, cuda::Rgba* out, unsigned long long* rays, cudaStream_t stream);
}
