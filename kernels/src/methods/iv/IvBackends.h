// The implicit-visibility method's stages and backends, as its MethodSpec creates them
// (IvMethod.cpp).
#pragma once

#include "engine/Pipeline.h"

namespace linkgi::iv
{
/// The stages, in the order of IvMethod.cpp's table.
enum Stage : std::size_t
{
  kElementStage,   ///< discs, one-ring, cluster tree build or refit, shadow-ray BVH
  kLinkStage,      ///< hierarchical links, refinement, push to the leaves
  kLightLinkStage, ///< shadow rays: E_d (the shared light-link code)
  kBounceStage     ///< E_env, gather / pull-up iterations, smoothing, outgoing radiance
};

/// Links the link stage holds at its peak, per vertex: node links gathered for the final
/// pass that keeps each receiving node's shortest per bin, the node links it keeps, and the
/// leaves' entries (transport and environment).
struct LinkCounts
{
  double created = 0.0, kept = 0.0, leafEntries = 0.0;
};

/// Host bytes per vertex that the link stage adds at its peak with `perVertex` links
/// (IvMethod.cpp): what the CPU backend's sample of the mesh returns
/// (MemoryShape::sampledPerElement), so that the estimate and the sample share one model.
double linkStageBytesPerVertex(const LinkCounts& perVertex);

std::unique_ptr<engine::MethodBackend> createCpuBackend(const SolverOptions& options);
#if LINKGI_HAVE_CUDA
/// One GPU (cuda/IvCuda.cpp); built with CUDA only.
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options);
#endif

const engine::MethodSpec& implicitVisibilityMethod();
}
