// Launchers of instant radiosity's CUDA kernels: host-callable, no __global__ here. The
// per-item math is IrMath.h's, the same the CPU runs; traversal is linkgi/Bvh.h's.
#pragma once

#include "ir/IrMath.h"

#include "cuda/Kernels.h"

namespace linkgi::ir::gpu
{
/// Light path p of scene.paths (device pointers in `scene`) into slots[p (bounces + 1), ...),
/// its VPL count into counts[p]: one thread per path.
void traceLightPaths(const PathScene& scene, const BvhView& bvh, Vpl* slots, int* counts,
  cudaStream_t stream);

/// What the gather reads on the device.
struct GatherLaunch
{
  BvhView visibility; ///< the mesh, or the proxy; no triangles = everything visible
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const Vec3f* shifts = nullptr;
  Index vertexCount = 0;
  bool twoSided = false;
  const Vpl* vpls = nullptr;
  const std::uint32_t* subsetOffsets = nullptr; ///< subsets + 1
  const float* subsetScale = nullptr;
  GatherParams params; ///< params.subsets: the number of subsets
};
/// out[e] = E_ind of element e from its VPL subset (gatherCpu's sum, same order); `rays`
/// adds the shadow rays traced. One thread per element.
void gatherVpls(const GatherLaunch& p, cuda::Rgba* out, unsigned long long* rays, cudaStream_t stream);
}
