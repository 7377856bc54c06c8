// Launchers of instant radiosity's CUDA kernels: host-callable, no __global__ here. The
// per-item math is IrMath.h's, the same the CPU runs; traversal is linkgi/Bvh.h's.
#pragma once

#include "methods/ir/IrHost.h"
#include "methods/ir/IrMath.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"
#include "cuda/LightPathKernels.h"
#include "cuda/OneDevice.h"

namespace linkgi::ir::gpu
{
using namespace linkgi::paths::gpu; // the light paths that leave the VPLs
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

/// What the clamp's compensation reads on the device (compensateCpu's inputs).
struct CompensationLaunch
{
  BvhView mesh;
  CompensationInputs inputs; ///< device arrays
  const cuda::Rgba* indirect = nullptr; ///< E_ind per element, as gathered
  std::uint32_t side = 0;               ///< k: k*k rays per element
  std::uint32_t seed = 0;
};

/// out[e] = indirect[e] plus the clamp's compensation at element e (compensateCpu's sums,
/// in the same order). One thread per element.
void compensate(const CompensationLaunch& p, cuda::Rgba* out, cudaStream_t stream);

/// The elements (both sides when twoSided) sorted by their VPL subset (vertexSubset), in
/// element order within a subset, into `order`; `keys`, `ids` and `temp` are scratch.
void elementsBySubset(Index vertexCount, bool twoSided, std::uint32_t subsets, std::uint32_t seed,
  cuda::GPUBuffer<std::uint64_t>& keys, cuda::GPUBuffer<Index>& ids, cuda::GPUBuffer<unsigned char>& temp,
  cuda::GPUBuffer<Index>& order, cudaStream_t stream);
/// out[e] = E_ind of element e from its VPL subset (gatherCpu's sum, same order); `rays`
/// adds the shadow rays traced. One thread per element.
void gatherVpls(const GatherLaunch& p, cuda::Rgba* out, unsigned long long* rays, cudaStream_t stream);
}
