// Photon mapping on the CPU: light paths and final-gather rays through the RayTracer
// interface (Embree or our BVH), loops on the engine's thread pool; the direct light is the
// shared light-link stage.
#include "methods/pm/PmBackends.h"

#include "methods/pm/PhotonMapping.h"

#include "cpu/CpuGeometry.h"
#include "engine/MemoryBudget.h"

#include "shared/DirectLight.h"
#include "shared/Sampling.h"

#include <memory>

namespace linkgi::pm
{
namespace
{
using namespace engine;

class PmCpu final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    switch (stage)
    {
      case kGeometryStage:
        geometryTouched = true;
        geometry.update(c);
        surface = std::make_unique<SurfaceTree>(c.scene);
        return;
      case kPhotonStage:
        return tracePhotons(c);
      case kClusterStage:
        clusters.stage() = clusterVertices(c.scene, c.options.photonMapping.clusters,
          c.options.photonMapping.alpha, kMeansIterations, c.progress);
        return;
      case kLightLinkStage:
        direct.stage() = computeDirectLight(c.scene, geometry.topology, geometry.origins,
          *geometry.tracer, c.options.twoSided, c.options.lightOversampling, c.progress);
        return;
      case kGatherStage:
        return gather(c);
      case kFinishStage:
        finishSolution(c, geometry.topology, gathered.now().irradiance, direct.now().irradiance);
        c.solution.caustics = gathered.now().caustics;
        return;
    }
  }

  void commit() override
  {
    map.commit();
    clusters.commit();
    direct.commit();
    gathered.commit();
    geometryTouched = false;
  }

  bool discard() override
  {
    map.discard();
    clusters.discard();
    direct.discard();
    gathered.discard();
    // The tracer and the host geometry are updated in place (see LinksCpu).
    const bool whole = !geometryTouched;
    geometryTouched = false;
    return whole;
  }

  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.rays = gathered.committed().rays;
    st.lightRays = direct.committed().shadowRays;
    st.setCounter("Photons", map.committed().count());
    st.setCounter("Clusters", clusters.committed().count());
  }

  const RayTracer* sceneTracer() const override { return geometry.tracer.get(); }

private:
  /// The gather stage's results: E_ind per element (caustics included), the caustics alone
  /// (front sides; empty without caustic photons) and the rays it traced.
  struct Gathered
  {
    std::vector<Vec3f> irradiance, caustics;
    std::uint64_t rays = 0;
  };

  void tracePhotons(const StageContext& c)
  {
    const auto half = [&c](double lo) -> ProgressCallback {
      return [&c, lo](const char*, double f) { return !c.progress || c.progress("Photons", lo + 0.5 * f); };
    };
    PhotonMap& next = map.stage();
    const std::uint64_t held = lightPathsHeldBytes(c);
    const std::uint64_t secondPass = linkgi::pm::tracePhotons(c.scene, geometry.faceNormals, geometry.origins,
      *geometry.tracer, c.options, next, half(0.0), memoryLeft(c.stats, held));
    raiseEstimate(c.stats, held + secondPass);
    estimateRadiance(next, surface->view(c.options.twoSided), c.options.photonMapping.estimatePhotons,
      siteStride(next.count()), kEstimateRadius * boundingDiagonal(c.scene.positions), half(0.5));
  }

  void gather(const StageContext& c)
  {
    const Scene& s = c.scene;
    const SolverOptions& o = c.options;
    const PhotonMap& photons = map.now();
    const Clusters& groups = clusters.now();
    const std::vector<Vec3f> directions = makeDirectionSet(o.photonMapping.gatherRays);
    // Under MPI each process gathers the clusters whose samples are its rows, and exchanges
    // complete them; every process then interpolates the whole surface.
    const std::size_t nv = s.vertexCount(), ne = Elements{ nv, o.twoSided }.count();
    const std::uint8_t* rows = ownRows(o, ne);
    Gathered& out = gathered.stage();
    out = Gathered();
    for (const float side : { 1.f, -1.f })
    {
      if (side < 0.f && !o.twoSided)
      {
        break;
      }
      const std::uint8_t* sideRows = rows ? rows + (side > 0.f ? 0 : nv) : nullptr;
      SampleIrradiance samples = finalGather(s, geometry.origins, geometry.faceNormals,
        *geometry.tracer, photons, groups, directions, o.seed, side, o.twoSided, c.progress, sideRows);
      if (rows)
      {
        completeSamples(o, groups, ne, samples);
      }
      const std::vector<Vec3f> e = interpolate(s, groups, samples);
      out.irradiance.insert(out.irradiance.end(), e.begin(), e.end());
      out.rays += samples.rays;
    }
    // Caustics, on the front sides: density estimation at every vertex, part of E_ind.
    if (!photons.causticPositions.empty())
    {
      out.caustics = causticIrradiance(s, photons, o.photonMapping.estimatePhotons,
        kCausticRadius * boundingDiagonal(s.positions), {}, rows);
      out.caustics.resize(ne, Vec3f(0.f)); // backs: none
      if (rows)
      {
        o.partition->exchange(out.caustics);
      }
      for (std::size_t e = 0; e < ne; ++e)
      {
        out.irradiance[e] += out.caustics[e];
      }
    }
  }

  /// The processes' samples made whole: each cluster's values travel in its sample vertex's
  /// element of an exchanged vector (zero elsewhere, so the sums are exact).
  static void completeSamples(const SolverOptions& o, const Clusters& groups, std::size_t elements,
    SampleIrradiance& samples)
  {
    std::vector<Vec3f> packed(elements, Vec3f(0.f));
    for (std::size_t j = 0; j < groups.count(); ++j)
    {
      packed[groups.sample[j]] = samples.irradiance[j];
    }
    o.partition->exchange(packed);
    for (std::size_t j = 0; j < groups.count(); ++j)
    {
      samples.irradiance[j] = packed[groups.sample[j]];
      packed[groups.sample[j]] = Vec3f(samples.harmonicDistance[j], 0.f, 0.f);
    }
    o.partition->exchange(packed);
    for (std::size_t j = 0; j < groups.count(); ++j)
    {
      samples.harmonicDistance[j] = packed[groups.sample[j]].x;
    }
  }

  CpuGeometry geometry;
  std::unique_ptr<SurfaceTree> surface; ///< with the geometry
  bool geometryTouched = false;
  Staged<PhotonMap> map;
  Staged<Clusters> clusters;
  Staged<DirectLightResult> direct;
  Staged<Gathered> gathered;
};
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<PmCpu>();
}
}
