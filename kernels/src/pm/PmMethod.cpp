// Photon mapping with clustered final gather (Wang, Wang, Zhou & Guo 2009): its stages and
// what makes each stale. The pieces in pm/PhotonMapping.h, the CPU backend in PmCpu.cpp.
// Documentation/Methods.md, "Photon mapping".
#include "pm/PmBackends.h"

namespace linkgi::pm
{
namespace
{
using namespace engine;

class PhotonMappingMethod final : public MethodSpec
{
public:
  const char* name() const override { return "photon-mapping"; }
  bool carriesSpecular() const override { return true; }
  const std::vector<StageSpec>& stages() const override
  {
    constexpr std::uint32_t geometry = 1u << kGeometryStage;
    // Photons are traced again whenever anything a light path meets changed (as instant
    // radiosity's VPLs); the clusters depend on the geometry alone, so a light move keeps
    // them. Shares: cornell on the CPU.
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 3.0 },
      { "Photons", "PhotonTraces",
        kLights | kAlbedo | kEmission | kEnvironmentLayout | kEnvironmentRadiance | kSampling |
          kSides | kIteration | kMethodOptions,
        geometry, 25.0 },
      { "Clusters", "ClusterBuilds", kMethodOptions, geometry, 10.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, geometry, 7.0 },
      { "Gather", "GatherRuns", kSides | kSampling | kMethodOptions | kEnvironmentLayout | kEnvironmentRadiance,
        geometry | (1u << kPhotonStage) | (1u << kClusterStage), 50.0 },
      { "Finish", "", kEverything, geometry | (1u << kGatherStage) | (1u << kLightLinkStage), 1.0 },
    };
    return table;
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
};
}

const MethodSpec& photonMappingMethod()
{
  static const PhotonMappingMethod method;
  return method;
}
}
