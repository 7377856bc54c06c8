// Photon mapping on the CPU: light paths and final-gather rays through the RayTracer
// interface (Embree or our BVH), loops on the engine's thread pool; the direct light is the
// shared light-link stage.
#include "pm/PmBackends.h"

#include "pm/PhotonMapping.h"

#include "engine/CpuGeometry.h"

#include "linkgi/DirectLight.h"
#include "linkgi/Sampling.h"

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
        return geometry.update(c);
      case kPhotonStage:
        return tracePhotons(c);
      case kClusterStage:
        nextClusters = clusterVertices(c.scene, c.options.photonMapping.clusters,
          c.options.photonMapping.alpha, kMeansIterations, c.progress);
        clustersStaged = true;
        return;
      case kLightLinkStage:
        nextDirect = computeDirectLight(c.scene, geometry.topology, geometry.shifts,
          *geometry.tracer, c.options.twoSided, c.options.lightOversampling, c.progress);
        directStaged = true;
        return;
      case kGatherStage:
        return gather(c);
      case kFinishStage:
        finishSolution(c, geometry.topology, gatherStaged ? nextGathered : gathered,
          directStaged ? nextDirect.irradiance : direct.irradiance);
        c.solution.caustics = gatherStaged ? nextCaustics : caustics;
        return;
    }
  }

  void commit() override
  {
    if (mapStaged)
    {
      std::swap(map, nextMap);
    }
    if (clustersStaged)
    {
      std::swap(clusters, nextClusters);
    }
    if (directStaged)
    {
      std::swap(direct, nextDirect);
    }
    if (gatherStaged)
    {
      std::swap(gathered, nextGathered);
      std::swap(caustics, nextCaustics);
      gatherRays = nextGatherRays;
    }
    mapStaged = clustersStaged = directStaged = gatherStaged = geometryTouched = false;
  }

  bool discard() override
  {
    mapStaged = clustersStaged = directStaged = gatherStaged = false;
    // The tracer and the host geometry are updated in place (see LinksCpu).
    const bool whole = !geometryTouched;
    geometryTouched = false;
    return whole;
  }

  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.rays = gatherRays;
    st.linksRaw = st.linksCompressed = st.linkBytes = 0;
    st.lightRays = direct.shadowRays;
    st.photons = map.count();
    st.clusters = clusters.count();
  }

private:
  void tracePhotons(const StageContext& c)
  {
    const auto half = [&c](double lo) -> ProgressCallback {
      return [&c, lo](const char*, double f) { return !c.progress || c.progress("Photons", lo + 0.5 * f); };
    };
    linkgi::pm::tracePhotons(c.scene, geometry.faceNormals, *geometry.tracer, c.options, nextMap, half(0.0));
    estimateRadiance(nextMap, c.options.photonMapping.estimatePhotons, siteStride(nextMap.count()),
      kEstimateRadius * boundingDiagonal(c.scene.positions), half(0.5));
    mapStaged = true;
  }

  void gather(const StageContext& c)
  {
    const Scene& s = c.scene;
    const SolverOptions& o = c.options;
    const PhotonMap& photons = mapStaged ? nextMap : map;
    const Clusters& groups = clustersStaged ? nextClusters : clusters;
    const std::vector<Vec3f> directions = makeDirectionSet(o.photonMapping.gatherRays);
    // Under MPI each process gathers the clusters whose samples are its rows, and exchanges
    // complete them; every process then interpolates the whole surface.
    const std::size_t nv = s.vertexCount();
    const std::uint8_t* rows = ownRows(o, Elements{ nv, o.twoSided }.count());
    nextGathered.clear();
    nextGatherRays = 0;
    for (const float side : { 1.f, -1.f })
    {
      if (side < 0.f && !o.twoSided)
      {
        break;
      }
      const std::uint8_t* sideRows = rows ? rows + (side > 0.f ? 0 : nv) : nullptr;
      SampleIrradiance samples = finalGather(s, geometry.shifts, geometry.faceNormals,
        *geometry.tracer, photons, groups, directions, o.seed, side, o.twoSided, c.progress, sideRows);
      if (rows)
      {
        completeSamples(o, groups, Elements{ nv, o.twoSided }.count(), samples);
      }
      const std::vector<Vec3f> e = interpolate(s, groups, samples);
      nextGathered.insert(nextGathered.end(), e.begin(), e.end());
      nextGatherRays += samples.rays;
    }
    // Caustics, on the front sides: density estimation at every vertex, part of E_ind.
    nextCaustics.clear();
    if (!photons.causticPositions.empty())
    {
      nextCaustics = causticIrradiance(s, photons, o.photonMapping.estimatePhotons,
        kCausticRadius * boundingDiagonal(s.positions), {}, rows);
      nextCaustics.resize(nextGathered.size(), Vec3f(0.f)); // backs: none
      if (rows)
      {
        o.partition->exchange(nextCaustics);
      }
      for (std::size_t e = 0; e < nextGathered.size(); ++e)
      {
        nextGathered[e] += nextCaustics[e];
      }
    }
    gatherStaged = true;
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
  bool geometryTouched = false;
  PhotonMap map, nextMap;
  Clusters clusters, nextClusters;
  DirectLightResult direct, nextDirect;
  std::vector<Vec3f> gathered, nextGathered, caustics, nextCaustics;
  std::uint64_t gatherRays = 0, nextGatherRays = 0;
  bool mapStaged = false, clustersStaged = false, directStaged = false, gatherStaged = false;
};
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<PmCpu>();
}
}
