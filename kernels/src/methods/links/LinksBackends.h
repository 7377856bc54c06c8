// The link-structure method's backends, as its MethodSpec creates them (LinksMethod.cpp).
#pragma once

#include "engine/Pipeline.h"
#include "methods/links/Links.h"

namespace linkgi::links
{
/// The stages, in the order of LinksMethod.cpp's table.
enum Stage : std::size_t
{
  kGeometryStage,   ///< topology, ray origins, face normals, acceleration structure
  kLinkStage,       ///< link rays and their compression into W and Wenv
  kLightLinkStage,  ///< shadow rays: E_d
  kBounceStage      ///< E_env, Jacobi bounces, smoothing, outgoing radiance
};

/// The detail nodes' columns (DetailNodes::columns) that a mesh of this shape may have.
std::uint64_t detailColumnBound(const MemoryShape& shape, const SolverOptions& options);

/// LinksPerElement::bound for a mesh of this shape under these options.
LinksPerElement linksPerElement(const MemoryShape& shape, const SolverOptions& options);

/// The links (transport and environment) per row that the CPU backend's peak is estimated
/// with: what a sample of rows made (shape.sampledPerElement) with a margin for the
/// sample's error, within the bound; the bound where nothing was sampled.
double estimatedLinksPerRow(const MemoryShape& shape, const SolverOptions& options);

/// The CPU backend's peak bytes for the stages `stale` (LinksCpu.cpp, beside what it allocates).
MemoryEstimate estimateCpuMemory(const MemoryShape& shape, const SolverOptions& options, std::uint32_t stale);

/// Embree (or our BVH) and all cores.
std::unique_ptr<engine::MethodBackend> createCpuBackend(const SolverOptions& options);
#if LINKGI_HAVE_CUDA
/// The CUDA engine (cuda/LinksCuda.cpp); built with CUDA only.
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options);
#endif
}
