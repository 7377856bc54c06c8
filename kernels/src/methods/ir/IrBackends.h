// The instant-radiosity method's stages and backends, as its MethodSpec creates them
// (IrMethod.cpp).
#pragma once

#include "engine/Pipeline.h"

#include <cstdint>

namespace linkgi::ir
{
/// The stages, in the order of IrMethod.cpp's table.
enum Stage : std::size_t
{
  kGeometryStage,  ///< topology, ray origins, face normals, acceleration structure
  kProxyStage,     ///< the coarse visibility proxy (nothing when proxy visibility is off)
  kVplStage,       ///< light paths from every source: the VPL set
  kLightLinkStage, ///< shadow rays to the point, spot and directional lights: E_d
  kGatherStage,    ///< per element: the sum over its VPL subset with visibility
  kFinishStage     ///< feature-aware smoothing, outgoing radiance, the output
};

/// Embree (or our BVH) and all cores (IrCpu.cpp).
std::unique_ptr<engine::MethodBackend> createCpuBackend(const SolverOptions& options);
#if LINKGI_HAVE_CUDA
/// The GPU (IrCuda.cpp); built with CUDA only.
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options);
#endif
}

#include "methods/ir/IrHost.h"

namespace linkgi::ir
{
/// E_ind per element (both sides when twoSided): each gathers its VPL subset, shadow rays
/// against `visibility` (the mesh, or the proxy when params.proxyMargin > 0). `rays` gets
/// the shadow rays traced. With `rows` (one flag per element), only those elements gather;
/// the others are zero.
std::vector<Vec3f> gatherCpu(const Scene& scene, const std::vector<RayOrigin>& origins,
  const VplSet& vpls, const RayTracer* visibility, const GatherParams& params, bool twoSided,
  std::uint64_t* rays = nullptr, const ProgressCallback& progress = {}, const std::uint8_t* rows = nullptr);

/// `indirect` plus the clamp's bias compensation (compensationSample, IrMath.h) at every
/// element: `rays` (k*k) rays per element against `tracer`, from the ray origins.
std::vector<Vec3f> compensateCpu(const Scene& scene, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const CompensationInputs& inputs, const std::vector<Vec3f>& indirect,
  std::uint32_t rays, std::uint32_t seed);

#if LINKGI_HAVE_CUDA
/// The same gather on the first GPU (mesh, BVH and shifts built there; exact visibility):
/// for comparing the backends on one VPL set. Throws CudaError without a device or CUDA.
std::vector<Vec3f> gatherCuda(const Scene& scene, const VplSet& vpls, const GatherParams& params,
  bool twoSided);
#endif
}
