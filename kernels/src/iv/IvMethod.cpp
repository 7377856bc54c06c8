// The implicit-visibility method (Dong, Kautz, Theobalt & Seidel 2007): its stages and what
// makes each stale. Formulas in ClusterTree.h and ImplicitLinks.h; the CPU backend in
// IvCpu.cpp, the CUDA backend in IvCuda.cpp. Documentation/Methods.md, "Implicit visibility".
#include "iv/IvBackends.h"

namespace linkgi::iv
{
namespace
{
using namespace engine;

class ImplicitVisibilityMethod final : public MethodSpec
{
public:
  const char* name() const override { return "implicit-visibility"; }
  const std::vector<StageSpec>& stages() const override
  {
    // The links are rebuilt whenever the geometry moves: that is the method (no rays, so
    // a new structure per frame is affordable). kSampling holds the partition's rows under
    // MPI (which leaves a process pushes to); the method reads none of its rays, twist and
    // seed. Shares: torso on the CPU at N = 12.
    static const std::vector<StageSpec> table = {
      { "Elements", "ElementUpdates", kGeometry, 0u, 5.0 },
      { "ImplicitLinks", "ImplicitLinkBuilds", kMethodOptions | kEnvironmentLayout | kSampling, 1u << kElementStage, 80.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, 1u << kElementStage, 10.0 },
      { "Bounces", "BounceRuns", kEverything, (1u << kElementStage) | (1u << kLinkStage) | (1u << kLightLinkStage), 5.0 },
    };
    return table;
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
};
}

const MethodSpec& implicitVisibilityMethod()
{
  static const ImplicitVisibilityMethod method;
  return method;
}
}
