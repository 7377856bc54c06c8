// The implicit-visibility method on the CPU: the cluster tree, links and gathers on all
// cores (the engine's thread pool); shadow rays for the point, spot and directional lights
// through the shared light-link code on Embree (or our BVH).
#include "methods/iv/ImplicitLinks.h"
#include "methods/iv/IvBackends.h"

#include "cpu/CpuGeometry.h"

#include "shared/DirectLight.h"
#include "linkgi/Error.h"
#include "shared/Surface.h"
#include "shared/Metrics.h"

#include <chrono>
#include <cmath>

namespace linkgi::iv
{
namespace
{
using namespace engine;

class IvCpu final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    switch (stage)
    {
      case kElementStage:
        return updateElements(c);
      case kLinkStage:
        return buildLinks(c);
      case kLightLinkStage:
        return lightLinks(c);
      case kBounceStage:
        return bounce(c);
    }
  }

  void commit() override
  {
    links.commit();
    direct.commit();
    geometryTouched = false;
  }

  bool discard() override
  {
    links.discard();
    direct.discard();
    // The tree, the tracer and the one-ring are updated in place: after a failure they may
    // belong to the failed scene, and the next update must rebuild them.
    const bool whole = !geometryTouched;
    geometryTouched = false;
    return whole;
  }

  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.rays = 0; // visibility is implied: no link rays
    const Links& l = links.committed();
    st.setCounter("LinksRaw", l.nodeLinks);
    st.setCounter("LinksCompressed", l.leaves.transport.nonZeros());
    st.setCounter("LinkBytes", l.leaves.transport.bytes() + l.leaves.environment.bytes());
    st.lightRays = direct.committed().shadowRays;
  }

private:
  void updateElements(const StageContext& c)
  {
    const Scene& s = c.scene;
    geometryTouched = true;
    geometry.update(c); // one-ring, ray origins, shadow-ray BVH (shared)
    const auto t = std::chrono::steady_clock::now();
    areas = vertexAreas(s);
    if ((c.changes & kTopology) || tree.leafCount != s.vertexCount())
    {
      tree = ClusterTree::build(s, areas);
      elements = ElementTriangles::of(s);
      c.part("HierarchyBuild", msSince(t));
    }
    else
    {
      tree.refit(s, areas);
      c.part("HierarchyRefit", msSince(t));
    }
  }

  void buildLinks(const StageContext& c)
  {
    const int n = int(c.options.implicitVisibility.binsPerSide);
    if (bins.n != n)
    {
      bins = CubeBins::make(n);
    }
    const LinkCreationOptions lo = LinkCreationOptions::of(c.scene);
    const auto within = [&c](double lo, double hi) -> ProgressCallback {
      return [&c, lo, hi](const char*, double f) { return !c.progress || c.progress("ImplicitLinks", lo + (hi - lo) * f); };
    };
    // Under MPI each process creates the links into its own leaves' ancestors only and
    // pushes them to its own leaves (its rows of the bounces).
    const std::uint8_t* rows = ownRows(c.options, c.scene.vertexCount());
    const NodeLinks created = createNodeLinks(tree, bins, lo, within(0.0, 0.6), rows);
    const auto t = std::chrono::steady_clock::now();
    Links& next = links.stage();
    next.leaves = pushToLeaves(tree, created, bins, c.scene, geometry.faceNormals, elements, geometry.origins, within(0.6, 1.0), rows);
    next.nodeLinks = created.byReceiver.nonZeros();
    c.part("RefinePush", msSince(t));
  }

  void lightLinks(const StageContext& c)
  {
    direct.stage() = computeDirectLight(c.scene, geometry.topology, geometry.origins, *geometry.tracer, false,
      c.options.lightOversampling, c.progress);
  }

  void bounce(const StageContext& c)
  {
    const Scene& s = c.scene;
    const SolverOptions& o = c.options;
    const LeafLinks& linksNow = links.now().leaves;
    const DirectLightResult& directNow = direct.now();
    const std::size_t nv = s.vertexCount();

    const std::vector<Vec3f> texels = environmentTexelRadiance(s.environment);
    std::vector<Vec3f> envIrradiance(nv);
    gatherRgb(linksNow.environment, texels.data(), envIrradiance.data());
    const bool partitioned = ownRows(o, nv) != nullptr;
    if (partitioned)
    {
      o.partition->exchange(envIrradiance); // the other processes' rows
    }
    BounceInputs inputs;
    inputs.fixedIrradiance.resize(nv);
    for (std::size_t v = 0; v < nv; ++v)
    {
      inputs.fixedIrradiance[v] = directNow.irradiance[v] + envIrradiance[v];
    }
    inputs.albedo = s.albedo;
    inputs.emission = s.emission;
    std::vector<Vec3f> indirect = iterateHierarchicalBounces(tree, linksNow.transport, inputs, o.bounces, c.progress,
      exchangeOf(o));
    for (std::size_t v = 0; v < nv; ++v)
    {
      indirect[v] += envIrradiance[v];
    }
    finishSolution(c, geometry.topology, std::move(indirect), directNow.irradiance); // one-sided
  }

  CpuGeometry geometry;
  std::vector<float> areas;
  ClusterTree tree;
  ElementTriangles elements;
  CubeBins bins;
  bool geometryTouched = false;
  /// The link stage's results: the leaves' links, and how many node links made them.
  struct Links
  {
    LeafLinks leaves;
    std::uint64_t nodeLinks = 0;
  };
  Staged<Links> links;
  Staged<DirectLightResult> direct;
};
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<IvCpu>();
}
}
