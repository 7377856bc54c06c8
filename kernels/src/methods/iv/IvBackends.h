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

std::unique_ptr<engine::MethodBackend> createCpuBackend(const SolverOptions& options);
#if LINKGI_HAVE_CUDA
/// One GPU (cuda/IvCuda.cpp); built with CUDA only.
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options);
#endif

const engine::MethodSpec& implicitVisibilityMethod();
}
