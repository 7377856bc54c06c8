// The link-structure method (Schmitz, Tavenrath & Kobbelt 2008): its stages and what makes
// each stale. The formulas live in Links.h, DirectLight.h and Bounce.h; the backends in
// LinksCpu.cpp and cuda/LinksCuda.cpp.
#include "links/LinksBackends.h"

namespace linkgi::links
{
namespace
{
using namespace engine;

class LinksMethod final : public MethodSpec
{
public:
  const char* name() const override { return "links"; }
  const std::vector<StageSpec>& stages() const override
  {
    // Progress shares: a full update of conference on the CPU spends ~85% in the links.
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 5.0 },
      { "Links", "LinkBuilds", kSampling | kSides | kEnvironmentLayout, 1u << kGeometryStage, 80.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, 1u << kGeometryStage, 10.0 },
      { "Bounces", "BounceRuns", kEverything, (1u << kGeometryStage) | (1u << kLinkStage) | (1u << kLightLinkStage), 5.0 },
    };
    return table;
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
};
}

const MethodSpec& linksMethod()
{
  static const LinksMethod method;
  return method;
}
}
