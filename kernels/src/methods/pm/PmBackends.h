// The photon-mapping method's stages and backends, as its MethodSpec creates them
// (PmMethod.cpp).
#pragma once

#include "engine/Pipeline.h"

namespace linkgi::pm
{
/// The stages, in the order of PmMethod.cpp's table.
enum Stage : std::size_t
{
  kGeometryStage,  ///< topology, ray origins, face normals, acceleration structure
  kPhotonStage,    ///< light paths from every source: the photon map and its estimates
  kClusterStage,   ///< the vertices' clusters, their samples and interpolants
  kLightLinkStage, ///< shadow rays to the point, spot and directional lights: E_d
  kGatherStage,    ///< final gather at the samples, interpolated to every vertex
  kFinishStage     ///< feature-aware smoothing, outgoing radiance, the output
};

/// Embree (or our BVH) and all cores (PmCpu.cpp).
std::unique_ptr<engine::MethodBackend> createCpuBackend(const SolverOptions& options);
#if LINKGI_HAVE_CUDA
/// The GPU (PmCuda.cpp); built with CUDA only.
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options);
#endif

#if LINKGI_HAVE_CUDA
/// The kd-tree the GPU builds over `points` (PointTreeView's order and axes, downloaded),
/// for tests that search it on the host. Throws CudaError without a device or CUDA.
void buildTreeOnDevice(const std::vector<Vec3f>& points, std::vector<Index>& order, std::vector<std::uint8_t>& axes);
#endif
}
