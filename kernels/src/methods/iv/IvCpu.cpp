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
#include "shared/Sampling.h"

#include <algorithm>
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
    nodeDirect.commit();
    geometryTouched = false;
  }

  bool discard() override
  {
    links.discard();
    direct.discard();
    nodeDirect.discard();
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
    st.setCounter("LinksCreated", l.createdLinks);
    st.setCounter("LinksEnvironment", l.leaves.environment.nonZeros());
    st.setCounter("LinksCompressed", l.leaves.transport.nonZeros());
    st.setCounter("LinkBytes", l.leaves.transport.bytes() + l.leaves.environment.bytes());
    st.setCounter("DetailNodes", detail.nodes.size());
    st.lightRays = direct.committed().shadowRays;
  }

  const RayTracer* sceneTracer() const override { return geometry.tracer.get(); }

  double sampleMemory(const StageContext& c) override
  {
    // A tree refit to a new pose links much as it did: what its last build took, measured.
    // Otherwise leaves drawn by a hash of their index, each with probability p (a 256th of
    // them, at least 256), linked and pushed to as the stage does for all. A node's links
    // are created where a leaf below it was drawn: near the root always, at a leaf with
    // probability p; each is weighted by one over that probability (Horvitz-Thompson), so
    // the sum estimates the whole tree's. The leaves' entries: their mean over those drawn.
    // 4-11% over the whole tree's on the standard scenes, at 2-25% of a first update's time
    // (TestImplicitVisibility.TheSampledLeavesEstimateTheWholeTreesLinks). Under MPI the
    // leaves are drawn from this process's own, whose ancestors are all it links: a node's
    // chance is that of its own leaves, and the sum is what this process holds.
    const std::uint32_t n = c.options.implicitVisibility.binsPerSide;
    const std::size_t nv = c.scene.vertexCount();
    const std::uint8_t* own = ownRows(c.options, nv);
    if (measured.bytesPerVertex > 0.0 && measured.binsPerSide == n &&
      (own ? measured.rows == c.options.partition->rows : measured.rows.empty()))
    {
      return measured.bytesPerVertex;
    }
    const std::size_t mine = ownRowCount(c.options, nv);
    if (mine == 0)
    {
      return 0.0;
    }
    const double p = std::min(1.0, std::max(256.0, double(mine) / 256.0) / double(mine));
    std::vector<std::uint8_t> sample(nv, 0);
    std::size_t drawn = 0;
    for (std::size_t v = 0; v < nv; ++v)
    {
      sample[v] = (!own || own[v]) && (p >= 1.0 || hashToUnit(kSampleSeed, std::uint32_t(v)) < p);
      drawn += sample[v];
    }
    if (drawn == 0)
    {
      return 0.0;
    }
    useBins(c.options);
    std::vector<Index> created;
    const NodeLinks nodes = createNodeLinks(tree, bins, LinkCreationOptions::of(c.scene), {}, sample.data(), &created);
    const LeafLinks leaves = pushToLeaves(tree, nodes, bins, c.scene, geometry.faceNormals, elements, geometry.origins,
      geometry.tracer.get(), detail, {}, sample.data());
    std::vector<double> below(tree.nodeCount(), 0.0); // own leaves below each node
    for (std::size_t v = 0; v < tree.leafCount; ++v)
    {
      below[v] = !own || own[v] ? 1.0 : 0.0;
    }
    for (std::size_t i = 0; i < tree.left.size(); ++i)
    {
      below[tree.leafCount + i] = below[tree.left[i]] + below[tree.right[i]];
    }
    LinkCounts total;
    const std::vector<Offset>& kept = nodes.byReceiver.rowOffsets;
    for (std::size_t node = 0; node < tree.nodeCount(); ++node)
    {
      if (created[node] > 0)
      {
        const double weight = 1.0 / (1.0 - std::pow(1.0 - p, below[node]));
        total.created += weight * created[node];
        total.kept += weight * double(kept[node + 1] - kept[node]);
      }
    }
    total.created /= double(nv);
    total.kept /= double(nv);
    total.leafEntries = double(leaves.entries()) / double(drawn) * double(mine) / double(nv);
    return linkStageBytesPerVertex(total);
  }

private:
  /// The seed of the leaves that sampleMemory draws.
  static constexpr std::uint32_t kSampleSeed = 0x51a3u;

  void useBins(const SolverOptions& o)
  {
    const int n = int(o.implicitVisibility.binsPerSide);
    if (bins.n != n)
    {
      bins = CubeBins::make(n);
    }
  }

  void updateElements(const StageContext& c)
  {
    const Scene& s = c.scene;
    geometryTouched = true;
    geometry.update(c); // one-ring, ray origins, shadow-ray BVH (shared)
    const auto t = std::chrono::steady_clock::now();
    areas = vertexAreas(s);
    detail = detailNodes(s, detailNodeBudget(s.vertexCount()));
    if ((c.changes & kTopology) || tree.leafCount != s.vertexCount())
    {
      tree = ClusterTree::build(s, areas);
      elements = ElementTriangles::of(s);
      measured = {};
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
    useBins(c.options);
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
    next.leaves = pushToLeaves(tree, created, bins, c.scene, geometry.faceNormals, elements, geometry.origins,
      geometry.tracer.get(), detail, within(0.6, 1.0), rows);
    next.nodeLinks = created.byReceiver.nonZeros();
    next.createdLinks = created.created;
    const double nv = double(c.scene.vertexCount());
    measured = { linkStageBytesPerVertex({ double(next.createdLinks) / nv, double(next.nodeLinks) / nv,
                   double(next.leaves.entries()) / nv }),
      c.options.implicitVisibility.binsPerSide, rows ? c.options.partition->rows : std::vector<std::uint8_t>{} };
    c.part("RefinePush", msSince(t));
  }

  void lightLinks(const StageContext& c)
  {
    DirectLightResult& d = direct.stage();
    d = computeDirectLight(c.scene, geometry.topology, geometry.origins, *geometry.tracer, false,
      c.options.lightOversampling, c.progress);
    nodeDirect.stage() = detailNodeDirect(c.scene, detail, geometry.origins, geometry.faceNormals, *geometry.tracer,
      false, &d.shadowRays);
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
    // Detail nodes: their corners' radiance without the corners' direct light, and their own.
    inputs.extraColumns = detail.columns(false);
    inputs.extraRadiance = [&](Vec3f* radiance) {
      detailNodeRadiance(s, detail, false, directNow.irradiance.data(), nodeDirect.now().data(), tree.nodeCount(),
        radiance);
    };
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
  /// The link stage's results: the leaves' links, and how many node links made them (kept,
  /// and gathered for the final pass that kept them).
  struct Links
  {
    LeafLinks leaves;
    std::uint64_t nodeLinks = 0, createdLinks = 0;
  };
  Staged<Links> links;
  /// What the last link build on this tree took per vertex (linkStageBytesPerVertex of its
  /// counts) at `binsPerSide`, for the partition's `rows` (empty: all); none once the tree
  /// is rebuilt.
  struct Measured
  {
    double bytesPerVertex = 0.0;
    std::uint32_t binsPerSide = 0;
    std::vector<std::uint8_t> rows;
  } measured;
  Staged<DirectLightResult> direct;
  /// Large triangles' nodes (surface hits on them read the nodes) and their E_d.
  DetailNodes detail;
  Staged<std::vector<Vec3f>> nodeDirect;
};
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<IvCpu>();
}
}
