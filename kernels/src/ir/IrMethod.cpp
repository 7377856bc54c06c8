// Instant radiosity with virtual point lights (Keller 1997, as Marques & Santos 2010 run it),
// per vertex: nothing is precomputed, so a deformation costs what a light move costs. Its
// stages and what makes each stale; the formulas live in ir/IrMath.h, the backends in
// IrCpu.cpp and IrCuda.cpp.
#include "ir/IrBackends.h"

namespace linkgi::ir
{
namespace
{
using namespace engine;

class InstantRadiosityMethod final : public MethodSpec
{
public:
  const char* name() const override { return "instant-radiosity"; }
  const std::vector<StageSpec>& stages() const override
  {
    constexpr std::uint32_t geometry = 1u << kGeometryStage;
    // Every light path is traced again whenever anything it could meet changed: the lights,
    // the materials, the environment, the geometry (through the Geometry stage), the seed,
    // the sides, the bounce count or the method's options. That is the method's point: a
    // deformation costs what a light move costs. Progress shares: the gather is nearly all
    // of an update on either backend.
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 3.0 },
      { "Proxy", "ProxyBuilds", kMethodOptions, geometry, 1.0 },
      { "VPLs", "VplBuilds",
        kLights | kAlbedo | kEmission | kEnvironmentLayout | kEnvironmentRadiance | kSampling |
          kSides | kIteration | kMethodOptions,
        geometry, 3.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, geometry, 7.0 },
      { "Gather", "GatherRuns", kSides | kMethodOptions,
        geometry | (1u << kProxyStage) | (1u << kVplStage), 85.0 },
      { "Finish", "", kEverything, geometry | (1u << kGatherStage) | (1u << kLightLinkStage), 1.0 },
    };
    return table;
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
};
}

const MethodSpec& instantRadiosityMethod()
{
  static const InstantRadiosityMethod method;
  return method;
}
}
