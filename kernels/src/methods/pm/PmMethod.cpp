// Photon mapping with clustered final gather (Wang, Wang, Zhou & Guo 2009): its stages and
// what makes each stale. The pieces in pm/PhotonMapping.h, the CPU backend in PmCpu.cpp.
// Documentation/Methods.md, "Photon mapping".
#include "methods/pm/PmBackends.h"
#include "engine/Progression.h"

#include "cpu/CpuGeometry.h"
#include "shared/LightPaths.h"
#include "methods/pm/PhotonMapping.h"

namespace linkgi
{
bool operator==(const PhotonMappingOptions& a, const PhotonMappingOptions& b)
{
  return a.photons == b.photons && a.clusters == b.clusters && a.gatherRays == b.gatherRays &&
    a.estimatePhotons == b.estimatePhotons && a.alpha == b.alpha;
}
}

namespace linkgi::pm
{
namespace
{
using namespace engine;

/// Host bytes of an update: the geometry (and the surface's pieces with their tree); the photon stage's path slots (one Vpl per bounce
/// and path of the first pass; a second pass, up to 64 times as many paths where most leave
/// the scene, is checked against what the budget leaves beyond the geometry when it is
/// known, and the estimate raised to hold both: lightPathsHeldBytes) and the map (per photon: position, normal, flux, the
/// kd-tree's order, the estimates and their radii at every siteStride-th); per vertex the clusters'
/// assignment and interpolants; and the per-element vectors. On the GPU the host holds the
/// per-element vectors and the map it reads back.
MemoryEstimate estimatePmMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale, bool cuda)
{
  const std::uint64_t photons = o.photonMapping.photons;
  MemoryEstimate m;
  m.hostBytes = cpuSolutionBytes(shape, o);
  if (!cuda && (stale & (1u << kGeometryStage)))
  {
    // and the pieces the estimates measure their discs by (SurfaceTree): centroid, three
    // corners, normal, area, radius and their kd-tree's order and axis each, at most
    // kSurfacePieces more than the triangles
    m.hostBytes += cpuGeometryBytes(shape) + (shape.triangles + kSurfacePieces) *
      (5 * sizeof(Vec3f) + 2 * sizeof(float) + sizeof(Index) + sizeof(std::uint8_t));
  }
  if (stale & (1u << kPhotonStage))
  {
    SolverOptions paths = o;
    paths.instantRadiosity.vplCount = o.photonMapping.photons;
    const std::uint64_t sites = std::min<std::uint64_t>(kMaxSites, photons / siteStride(photons) + 1);
    m.hostBytes += (cuda ? 0 : std::uint64_t(paths::pathCount(paths)) * (o.bounces + 1) * (sizeof(paths::Vpl) + sizeof(int))) +
      photons * (3 * sizeof(Vec3f) + sizeof(Index)) + sites * (3 * sizeof(Vec3f) + sizeof(float) + sizeof(Index));
  }
  if (stale & (1u << kClusterStage))
  {
    m.hostBytes += shape.vertices * (1 + Clusters::kInterpolants) * sizeof(Index) * 2;
  }
  return m;
}

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
  void validateOptions(const SolverOptions& o) const override
  {
    const PhotonMappingOptions& pm = o.photonMapping;
    if (pm.photons < 1 || pm.photons > (1u << 24))
    {
      throw Error("Photon mapping: the number of photons must be between 1 and 16777216; got " +
        std::to_string(pm.photons) + ".");
    }
    if (pm.clusters < 1 || pm.clusters > (1u << 20))
    {
      throw Error("Photon mapping: the number of clusters must be between 1 and 1048576; got " +
        std::to_string(pm.clusters) + ".");
    }
    if (!isPerfectSquare(pm.gatherRays) || pm.gatherRays > 65536)
    {
      throw Error("Photon mapping: the final-gather rays per sample must be a perfect square up to "
                  "65536 (e.g. 64, 256, 1024); got " + std::to_string(pm.gatherRays) + ".");
    }
    if (pm.estimatePhotons < 2 || pm.estimatePhotons > 1024)
    {
      throw Error("Photon mapping: the photons per radiance estimate must be between 2 and 1024; got " +
        std::to_string(pm.estimatePhotons) + ".");
    }
    if (!(pm.alpha >= 0.f && pm.alpha <= 1000.f))
    {
      throw Error("Photon mapping: the clustering's distance weight alpha must be in [0, 1000]; got " +
        std::to_string(pm.alpha) + ".");
    }
  }
  bool optionsDiffer(const SolverOptions& a, const SolverOptions& b) const override
  {
    return a.photonMapping != b.photonMapping;
  }
  std::string sampling(const SolverOptions& o) const override
  {
    return std::to_string(o.photonMapping.photons) + " photons, " + std::to_string(o.photonMapping.gatherRays) +
      " gather rays";
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
#if LINKGI_HAVE_CUDA
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
  bool hasCudaBackend() const override { return true; }
#endif
  double sampleWork(std::size_t elements, const SolverOptions& o) const override
  {
    // The final gather at the sample vertices, and the photons' paths.
    const PhotonMappingOptions& p = o.photonMapping;
    return double(std::min<std::size_t>(p.clusters, elements)) * p.gatherRays + double(p.photons);
  }
  SolverOptions coarser(const SolverOptions& o, double fraction) const override
  {
    SolverOptions c = o;
    PhotonMappingOptions& p = c.photonMapping;
    p.gatherRays = scaledSquare(o.photonMapping.gatherRays, fraction, 16);
    p.photons = scaledCount(o.photonMapping.photons, fraction, std::min(o.photonMapping.photons, 4096u));
    return c;
  }
  MemoryEstimate estimateMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale,
    bool cuda) const override
  {
    return estimatePmMemory(shape, o, stale, cuda);
  }
};
}

const MethodSpec& photonMappingMethod()
{
  static const PhotonMappingMethod method;
  return method;
}
}
