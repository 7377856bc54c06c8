// The implicit-visibility method on one GPU. The cluster tree is the host's (built when the
// topology changes, refit otherwise: ~1 ms on the torso) and goes up as one record per node;
// the pair recursion (one kernel per level of pairs), each node's shortest link per bin,
// the push to the leaves (one block per leaf, its bins in shared memory), the gathers and
// the pull-ups run on the device. The mesh, the direct light and the finish are the pieces
// every one-GPU backend shares (cuda/OneDevice.h). Formulas: iv/IvShared.h, as on the CPU.
#include "methods/iv/ImplicitLinks.h"
#include "methods/iv/IvBackends.h"
#include "methods/iv/cuda/IvKernels.h"

#include "cuda/DetailKernels.h"
#include "cuda/OneDevice.h"

#include "cuda/Cuda.h"
#include "shared/Metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>

namespace linkgi::iv
{
namespace
{
using namespace engine;
using cuda::GPUBuffer;
using cuda::Rgba;

class IvCuda final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    // Device state is updated in place: a failed update leaves it unusable (discard()).
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
  void commit() override {}
  bool discard() override { return false; }

  void describe(SolverStats& st) const override
  {
    device.describe(st);
    st.rays = 0; // visibility is implied: no link rays
    st.setCounter("LinksRaw", nodeLinks);
    st.setCounter("LinksCompressed", transportEntries);
    st.setCounter("LinkBytes", (transportEntries + environmentEntries) * (sizeof(Index) + sizeof(float)));
    st.setCounter("DetailNodes", detail.nodes.size());
    st.lightRays = lightRays;
  }

  const RayTracer* sceneTracer() const override { return meshTracer.get(); }

private:
  void updateElements(const StageContext& c)
  {
    const Scene& s = c.scene;
    mesh.update(s, c.changes, stream, &c.stats);
    // The large triangles' nodes laid out on another host thread while this one builds or
    // refits the tree (1-4 ms on 150k triangles).
    std::future<DetailNodes> nextDetail =
      std::async(std::launch::async, [&s] { return detailNodes(s, detailNodeBudget(s.vertexCount())); });
    const auto t = std::chrono::steady_clock::now();
    const std::vector<float> areas = vertexAreas(s);
    if ((c.changes & kTopology) || tree.leafCount != s.vertexCount())
    {
      tree = ClusterTree::build(s, areas);
      uploadStructure();
      const ElementTriangles elements = ElementTriangles::of(s);
      elementOffsets.upload(elements.offsets, stream);
      elementTriangles.upload(elements.triangles, stream);
      c.part("HierarchyBuild", msSince(t));
    }
    else
    {
      tree.refit(s, areas);
      c.part("HierarchyRefit", msSince(t));
    }
    nodes.upload(nodeBounds(tree), stream);
    area.upload(tree.area, stream);
    extents.upload(tree.extent, stream);
    extentSlabs.upload(tree.extentSlab, stream);
    detail = nextDetail.get();
    detailFirst.upload(detail.first, stream);
    detailSteps.upload(detail.steps, stream);
    detailNodeList.upload(detail.nodes, stream);
    linkOptions = LinkCreationOptions::of(s); // a pass over the positions: once per geometry
  }

  /// What does not move with the vertices: children, parents, and the interior nodes by
  /// height for the pull-up (nodes of one height do not depend on each other).
  void uploadStructure()
  {
    const std::size_t leaves = tree.leafCount, interior = tree.left.size();
    std::vector<Index> height(tree.nodeCount(), 0);
    Index tallest = 0;
    for (std::size_t i = 0; i < interior; ++i)
    {
      const std::size_t id = leaves + i;
      height[id] = 1 + std::max(height[tree.left[i]], height[tree.right[i]]);
      tallest = std::max(tallest, height[id]);
    }
    levelOffsets.assign(std::size_t(tallest) + 1, 0);
    for (std::size_t i = 0; i < interior; ++i)
    {
      ++levelOffsets[height[leaves + i]]; // counts of height h at [h], h >= 1
    }
    Index sum = 0;
    for (Index& o : levelOffsets)
    {
      const Index n = o;
      o = sum;
      sum += n;
    }
    levelOffsets.push_back(sum);
    levelOffsets.erase(levelOffsets.begin()); // level l = height l + 1
    std::vector<Index> order(interior), next(levelOffsets.begin(), levelOffsets.end() - 1);
    for (std::size_t i = 0; i < interior; ++i)
    {
      order[next[height[leaves + i] - 1]++] = Index(leaves + i);
    }
    levelNodes.upload(order, stream);
    left.upload(tree.left, stream);
    right.upload(tree.right, stream);
    parent.upload(tree.parent, stream);
  }

  void buildLinks(const StageContext& c)
  {
    const int n = int(c.options.implicitVisibility.binsPerSide);
    if (n > gpu::kMaxBinsPerSide)
    {
      throw CudaError("The implicit-visibility method on the GPU holds at most " +
          std::to_string(gpu::kMaxBinsPerSide) + " bins per side; " + std::to_string(n) + " were asked for.",
        false);
    }
    if (bins.n != n)
    {
      bins = CubeBins::make(n);
      binCenters.upload(bins.center, stream);
      binSolidAngles.upload(bins.solidAngle, stream);
    }
    std::vector<Index> texels(bins.count());
    for (std::size_t b = 0; b < bins.count(); ++b)
    {
      texels[b] = c.scene.environment.texelIndex(bins.center[b]);
    }
    binTexels.upload(texels, stream);

    // The pair recursion, breadth first: one launch per level of pairs, each level's
    // links and next pairs appended; a level that overflows its buffers runs again.
    const PairRules rules = pairRules(nodes.data(), left.data(), right.data(), extents.data(), extentSlabs.data(),
      tree.leafCount, bins, linkOptions);
    const gpu::NodePair root{ tree.root(), tree.root() };
    frontier.upload(&root, 1, stream);
    std::size_t frontierCount = 1, linkCount = 0;
    counters.resize(2);
    unsigned long long* pinned = device.counters + kNextSlot; // [next, links]
    while (frontierCount)
    {
      c.check(0.0);
      for (;;)
      {
        const unsigned long long start[2] = { 0, linkCount };
        LINKGI_CUDA_CHECK(cudaMemcpyAsync(counters.data(), start, sizeof start, cudaMemcpyHostToDevice, stream));
        const std::size_t nextRoom = std::max<std::size_t>(next.size(), 4 * frontierCount);
        next.resize(nextRoom);
        gpu::visitPairs(rules, frontier.data(), frontierCount, { next.data(), counters.data(), next.size() },
          { links.data(), counters.data() + 1, links.size() }, stream);
        LINKGI_CUDA_CHECK(cudaMemcpyAsync(pinned, counters.data(), 2 * sizeof(unsigned long long),
          cudaMemcpyDeviceToHost, stream));
        LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
        if (pinned[0] <= next.size() && pinned[1] <= links.size())
        {
          break;
        }
        // Too little room: grow (the links so far kept) and run the level again.
        next.resize(std::size_t(pinned[0]));
        links.growKeep(std::max<std::size_t>(std::size_t(pinned[1]) + std::size_t(pinned[1]) / 2, links.size()), stream);
      }
      linkCount = std::size_t(pinned[1]);
      frontierCount = std::size_t(pinned[0]);
      std::swap(frontier, next);
    }
    gpu::keepShortestPerBin(links.data(), linkCount, nodes.data(), extents.data(), tree.nodeCount(), n, nodeRows,
      stream);

    // A bin's key holds its column: the tree's nodes, then the detail nodes.
    if (tree.nodeCount() + detail.nodes.size() > kSourceMask)
    {
      throw Error("The implicit-visibility method holds at most " + std::to_string(kSourceMask / 2) +
        " vertices; the scene has " + std::to_string(tree.leafCount) + ".");
    }
    gpu::PushParams p;
    p.nodes = nodes.data();
    p.extents = extents.data();
    p.parent = parent.data();
    p.rowStarts = nodeRows.rowStarts.data();
    p.rowCounts = nodeRows.rowCounts.data();
    p.columns = nodeRows.columns.data();
    p.receivers = mesh.origins.data();
    p.positions = mesh.positions.data();
    p.triangles = mesh.triangles.data();
    p.faceNormals = mesh.faceNormals.data();
    p.bvh = mesh.bvh.view();
    p.elementOffsets = elementOffsets.data();
    p.elementTriangles = elementTriangles.data();
    p.binCenters = binCenters.data();
    p.binSolidAngles = binSolidAngles.data();
    p.binTexels = binTexels.data();
    p.leafCount = Index(tree.leafCount);
    p.binsPerSide = n;
    p.binAngle = std::sqrt(bins.meanSolidAngle());
    p.detail = detail.grid(tree.nodeCount(), detailFirst.data(), detailSteps.data()); // after the tree's nodes
    totals.resize(5);
    totals.fillZero(stream);
    stride = bins.count();
    gpu::pushToLeaves(p, stride, leafRows, totals.data(), stream);
    // The totals say how long the rows are (the bounces' threads per row) and whether a
    // leaf had more leaves to draw from their surface than the push holds.
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(device.counters + kTotalsSlot, totals.data(), 5 * sizeof(unsigned long long),
      cudaMemcpyDeviceToHost, stream));
    Offset lastStart = 0;
    Index lastCount = 0;
    if (tree.nodeCount())
    {
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(&lastStart, nodeRows.rowStarts.data() + tree.nodeCount() - 1, sizeof lastStart,
        cudaMemcpyDeviceToHost, stream));
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(&lastCount, nodeRows.rowCounts.data() + tree.nodeCount() - 1, sizeof lastCount,
        cudaMemcpyDeviceToHost, stream));
    }
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    const unsigned long long* t = device.counters + kTotalsSlot;
    if (t[4])
    {
      throw CudaError(std::to_string(t[4]) + " leaves had more neighbours to draw from their surface than the GPU's push holds.", false);
    }
    nodeLinks = lastStart + lastCount;
    transportEntries = t[2];
    environmentEntries = t[3];
  }

  void lightLinks(const StageContext& c)
  {
    direct.queue(c.scene, c.options, mesh, device.counters + kLightSlot, stream);
    nodeDirect.resize(std::max<std::size_t>(detail.nodes.size(), 1));
    nodeRays.resize(1);
    nodeRays.fillZero(stream);
    cuda::detailDirect(detailParams(), direct.lights.data(), Index(direct.lights.size()), nodeDirect.data(),
      nodeRays.data(), stream);
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(device.counters + kNodeLightSlot, nodeRays.data(), sizeof(unsigned long long),
      cudaMemcpyDeviceToHost, stream));
    lightPending = true;
  }

  cuda::CsrView view(const GPUBuffer<Index>& counts, const GPUBuffer<Index>& columns, const GPUBuffer<float>& weights,
    Offset entries) const
  {
    cuda::CsrView v;
    v.rowStarts = leafRows.rowStarts.data();
    v.rowCounts = counts.data();
    v.columns = columns.data();
    v.weights = weights.data();
    v.rows = Index(tree.leafCount);
    v.firstElement = 0;
    v.nonZeros = entries;
    v.lanes = cuda::lanesForRows(entries, tree.leafCount);
    return v;
  }

  /// The detail nodes' kernels' view of the mesh (one-sided).
  cuda::DetailParams detailParams() const
  {
    cuda::DetailParams d;
    d.bvh = mesh.bvh.view();
    d.triangles = mesh.triangles.data();
    d.positions = mesh.positions.data();
    d.normals = mesh.normals.data();
    d.faceNormals = mesh.faceNormals.data();
    d.origins = mesh.origins.data();
    d.nodes = detailNodeList.data();
    d.nodeCount = Index(detail.nodes.size());
    return d;
  }

  void bounce(const StageContext& c)
  {
    const Scene& s = c.scene;
    const SolverOptions& o = c.options;
    const std::size_t nv = tree.leafCount;
    if (c.changes & (kTopology | kAlbedo))
    {
      albedo.upload(s.albedo, stream);
    }
    if (c.changes & (kTopology | kEmission))
    {
      emission.upload(s.emission, stream);
    }
    std::vector<Rgba> texels;
    for (const Vec3f& r : environmentTexelRadiance(s.environment))
    {
      texels.push_back(cuda::toRgba(r));
    }
    texelRadiance.upload(texels, stream);
    for (GPUBuffer<Rgba>* b : { &envIrradiance, &fixed, &indirect })
    {
      b->resize(std::max<std::size_t>(nv, 1));
    }
    radiance.resize(std::max<std::size_t>(tree.nodeCount() + detail.nodes.size(), 1)); // the tree's, the nodes'
    cuda::gatherRgb(view(leafRows.envCounts, leafRows.envColumns, leafRows.envWeights, environmentEntries),
      texelRadiance.data(), envIrradiance.data(), stream);
    gpu::addDirect(direct.direct.data(), envIrradiance.data(), nv, fixed.data(), stream);
    indirect.fillZero(stream);
    gpu::TreeLevels levels;
    levels.left = left.data();
    levels.right = right.data();
    levels.area = area.data();
    levels.levelNodes = levelNodes.data();
    levels.leafCount = Index(nv);
    const Vec3f* le = s.emission.empty() ? nullptr : emission.data();
    const cuda::CsrView w = view(leafRows.counts, leafRows.columns, leafRows.weights, transportEntries);
    for (std::uint32_t b = 0; b < o.bounces; ++b)
    {
      c.check(double(b) / std::max(1u, o.bounces));
      gpu::leafRadianceAndPullUp(levels, levelOffsets, albedo.data(), le, fixed.data(), indirect.data(),
        radiance.data(), stream);
      cuda::detailRadiance(detailParams(), Index(tree.nodeCount()), Index(nv), direct.direct.data(), albedo.data(),
        nodeDirect.data(), radiance.data(), stream);
      cuda::gatherRgb(w, radiance.data(), indirect.data(), stream);
    }
    gpu::addTo(envIrradiance.data(), nv, indirect.data(), stream);
    done.run(s, o, mesh, direct.direct.data(), indirect.data(), albedo.data(), le, c.solution, {}, stream);
    if (lightPending)
    {
      lightRays = device.counters[kLightSlot] + device.counters[kNodeLightSlot];
      lightPending = false;
    }
  }

  /// counters' slots (pinned): the direct light's shadow rays, a level's [next pairs, links],
  /// the push's five totals.
  static constexpr int kLightSlot = 0, kNextSlot = 1, kTotalsSlot = 3, kNodeLightSlot = 8, kSlots = 9;

  cuda::DeviceContext device{ kSlots };
  cudaStream_t stream = device.stream;
  cuda::DeviceMesh mesh;
  /// The mesh's BVH for checks of a result (sceneTracer).
  std::unique_ptr<RayTracer> meshTracer = cuda::traceThrough(mesh.bvh, device.device, stream);
  cuda::DeviceDirectLight direct;
  cuda::DeviceFinish done;

  ClusterTree tree;
  CubeBins bins;
  LinkCreationOptions linkOptions;
  std::vector<Index> levelOffsets;
  GPUBuffer<NodeBounds> nodes;
  GPUBuffer<float> area, extents, extentSlabs, binSolidAngles;
  GPUBuffer<Index> left, right, parent, levelNodes, binTexels, elementOffsets, elementTriangles;
  GPUBuffer<Vec3f> binCenters, albedo, emission, nodeDirect;
  /// The large triangles' detail nodes (DetailNodes.h), their grids and E_d.
  DetailNodes detail;
  GPUBuffer<Index> detailFirst;
  GPUBuffer<std::uint16_t> detailSteps;
  GPUBuffer<DetailNode> detailNodeList;
  GPUBuffer<unsigned long long> nodeRays;
  GPUBuffer<gpu::NodePair> frontier, next, links;
  GPUBuffer<unsigned long long> counters, totals;
  gpu::NodeRows nodeRows;
  gpu::LeafRows leafRows;
  std::size_t stride = 0;
  GPUBuffer<Rgba> texelRadiance, envIrradiance, fixed, indirect, radiance;
  std::uint64_t nodeLinks = 0, transportEntries = 0, environmentEntries = 0, lightRays = 0;
  bool lightPending = false;
};
}

std::unique_ptr<MethodBackend> createCudaBackend(const SolverOptions&)
{
  return std::make_unique<IvCuda>();
}
}
