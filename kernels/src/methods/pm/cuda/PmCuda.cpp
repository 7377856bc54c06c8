// Photon mapping on one GPU: light paths (cuda/LightPathKernels.h), the photon map, its
// kd-trees and estimates, the final gather, the interpolation and the caustics stay on the
// device; the mesh, the direct light and the finish are the pieces every one-GPU backend
// shares (cuda/OneDevice.h). The clusters depend on the geometry alone and are the host's
// (clusterVertices), uploaded: a light move does not rebuild them. One stream: an update
// waits for the device where the host needs a number (paths' hits, photons stored) and once
// at the end, for the output.
#include "methods/pm/PmBackends.h"
#include "methods/pm/cuda/PmKernels.h"
#include "methods/pm/PhotonMapping.h"

#include "cuda/LightPathKernels.h"

#include "cuda/OneDevice.h"

#include "cuda/Cuda.h"
#include "shared/Metrics.h"
#include "shared/Sampling.h"

#include <cmath>

namespace linkgi::pm
{
namespace
{
using namespace engine;
using cuda::GPUBuffer;

class PmCuda final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    // Device state is updated in place: a failed update leaves it unusable (discard()).
    switch (stage)
    {
      case kGeometryStage:
        return geometry(c);
      case kPhotonStage:
        return tracePhotons(c);
      case kClusterStage:
        return cluster(c);
      case kLightLinkStage:
        return directLight(c);
      case kGatherStage:
        return gather(c);
      case kFinishStage:
        return finish(c);
    }
  }
  void commit() override {}
  bool discard() override { return false; }

  void describe(SolverStats& st) const override
  {
    device.describe(st);
    st.rays = gatherRays;
    st.lightRays = lightRays;
    st.setCounter("Photons", photonCount);
    st.setCounter("Clusters", clusterCount);
  }

  const RayTracer* sceneTracer() const override { return meshTracer.get(); }

private:
  void geometry(const StageContext& c)
  {
    mesh.update(c.scene, c.changes, stream, &c.stats);
    if (c.changes & (kTopology | kPositions))
    {
      areas.upload(vertexAreas(c.scene), stream); // the caustics' one-ring discs
      const SurfacePieces pieces = surfacePieces(c.scene);
      pieceCentroids.upload(pieces.centroids, stream);
      pieceCorners.upload(pieces.corners, stream);
      pieceNormals.upload(pieces.normals, stream);
      pieceAreas.upload(pieces.areas, stream);
      pieceRadii.upload(pieces.radii, stream);
      pieceReach = pieces.reach;
      pieceTree.build(pieceCentroids.data(), Index(pieces.centroids.size()), stream);
    }
  }

  void tracePhotons(const StageContext& c)
  {
    const Scene& s = c.scene;
    SolverOptions o = c.options;
    o.instantRadiosity.vplCount = o.photonMapping.photons;
    o.instantRadiosity.russianRoulette = true;
    const paths::PathSetup setup = paths::buildPathSetup(s, {}, {}, o, &mesh.extent);
    pathView = pathScene.upload(s, setup, c.changes, mesh, true, stream);
    paths::PathScene view = pathView;
    const std::size_t found = paths::gpu::traceAllPaths(view, mesh.bvh.view(), setup.targetVpls, paths,
      device.counters + kFoundSlot, stream);
    // The hits in path order (one subset), then split into photons and caustic photons.
    hits.resize(std::max<std::size_t>(found, 1));
    subsetOffsets.resize(2);
    subsetScale.resize(1);
    paths::gpu::packVpls(paths.slots.data(), paths.counts.data(), paths.pathOffsets.data(), view.paths,
      view.bounces + 1, 1, hits.data(), subsetOffsets.data(), subsetScale.data(), stream);
    static_assert(sizeof(Offset) == sizeof(unsigned long long), "photon totals land in counter slots");
    gpu::splitPhotons(hits.data(), found, photons, flags, scan, temp,
      reinterpret_cast<Offset*>(device.counters + kPhotonSlot), stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    photonCount = std::size_t(device.counters[kPhotonSlot]);
    causticCount = std::size_t(device.counters[kCausticSlot]);
    checkPhotonCount(photonCount);
    photonTree.build(photons.positions.data(), std::uint32_t(photonCount), stream);
    // Searches run on copies in the tree's order: neighbours in neighbouring memory.
    for (auto* a : { &sorted.positions, &sorted.normals, &sorted.flux })
    {
      a->resize(std::max<std::size_t>(photonCount, 1));
    }
    const PointTreeView photonView = photonTree.inTreeOrder({ { photons.positions.data(), sorted.positions.data() },
      { photons.normals.data(), sorted.normals.data() }, { photons.flux.data(), sorted.flux.data() } }, stream);
    const std::uint32_t stride = siteStride(photonCount);
    siteCount = std::uint32_t((photonCount + stride - 1) / stride);
    for (auto* a : { &sitePositions, &siteNormals, &siteRadiance, &sites.positions, &sites.normals, &sites.flux })
    {
      a->resize(std::max<std::uint32_t>(siteCount, 1));
    }
    siteRadius2.resize(std::max<std::uint32_t>(siteCount, 1));
    treeRadius2.resize(std::max<std::uint32_t>(siteCount, 1));
    const float radius = kEstimateRadius * mesh.extent.diagonal;
    estimateMax2 = radius * radius;
    gpu::estimateSites({ photonView, sorted.normals.data(), sorted.flux.data() }, photonTree.view().order,
      { pieceTree.view(), pieceCorners.data(), pieceNormals.data(), pieceAreas.data(), pieceRadii.data(), pieceReach,
        o.twoSided }, stride, o.photonMapping.estimatePhotons, estimateMax2, sitePositions.data(), siteNormals.data(), siteRadiance.data(),
      siteRadius2.data(), flags, scan, temp, stream);
    siteTree.build(sitePositions.data(), siteCount, stream);
    // The estimates in the site tree's order (their radiance in `flux`'s place).
    siteView = siteTree.inTreeOrder({ { sitePositions.data(), sites.positions.data() },
      { siteNormals.data(), sites.normals.data() }, { siteRadiance.data(), sites.flux.data() } }, stream);
    siteTree.inTreeOrder(siteRadius2.data(), treeRadius2.data(), stream);
    causticTree.build(photons.causticPositions.data(), std::uint32_t(causticCount), stream);
  }

  static void checkPhotonCount(std::size_t n)
  {
    // The kd-tree's sort counts in int (CUB); PhotonMappingOptions caps photons at 2^24.
    if (n >= (std::size_t(1) << 31))
    {
      throw CudaError("Photon mapping on the GPU holds at most 2^31 photons; " + std::to_string(n) +
        " were stored.", false);
    }
  }

  void cluster(const StageContext& c)
  {
    const Clusters clusters = clusterVertices(c.scene, c.options.photonMapping.clusters,
      c.options.photonMapping.alpha, kMeansIterations, c.progress);
    samples.upload(clusters.sample, stream);
    neighbours.upload(clusters.neighbours, stream);
    clusterCount = clusters.count();
  }

  void directLight(const StageContext& c)
  {
    direct.queue(c.scene, c.options, mesh, device.counters + kLightSlot, stream);
    lightPending = true;
  }

  void gather(const StageContext& c)
  {
    const SolverOptions& o = c.options;
    const Index nv = mesh.vertexCount;
    if (directions.size() != o.photonMapping.gatherRays)
    {
      directions.upload(makeDirectionSet(o.photonMapping.gatherRays), stream);
    }
    // Caustics, on the front sides: density estimation at every vertex, part of E_ind.
    if (causticCount)
    {
      caustics.resize(nv);
      const float radius = kCausticRadius * mesh.extent.diagonal;
      gpu::causticIrradiance({ causticTree.view(), photons.causticNormals.data(), photons.causticFlux.data() },
        mesh.positions.data(), mesh.normals.data(), pathScene.albedo.data(), areas.data(), nv,
        o.photonMapping.estimatePhotons, radius * radius, caustics.data(), stream);
    }
    gpu::GatherLaunch g;
    g.scene = pathView; // the gather runs whenever the photons were traced again for its inputs
    g.bvh = mesh.bvh.view();
    g.sites = { siteView, sites.normals.data(), sites.flux.data(), treeRadius2.data(), estimateMax2 };
    g.samples = samples.data();
    g.clusters = std::uint32_t(clusterCount);
    g.vertexCount = nv;
    g.directions = directions.data();
    g.directionCount = o.photonMapping.gatherRays;
    g.seed = o.seed;
    g.twoSided = o.twoSided;
    g.diagonal = mesh.extent.diagonal;
    const Elements elements{ nv, o.twoSided };
    gathered.resize(elements.count());
    sampleIrradiance.resize(std::max<std::size_t>(clusterCount, 1));
    harmonicDistance.resize(std::max<std::size_t>(clusterCount, 1));
    gatherRays = 0;
    for (const float side : { 1.f, -1.f })
    {
      if (side < 0.f && !o.twoSided)
      {
        break;
      }
      g.side = side;
      gpu::finalGather(g, sampleIrradiance.data(), harmonicDistance.data(), stream);
      gpu::interpolate(mesh.positions.data(), mesh.normals.data(), nv, neighbours.data(), samples.data(),
        sampleIrradiance.data(), harmonicDistance.data(), side > 0.f && causticCount ? caustics.data() : nullptr,
        gathered.data() + (side > 0.f ? 0 : nv), stream);
      gatherRays += std::uint64_t(clusterCount) * o.photonMapping.gatherRays;
    }
    gatherRan = true;
  }

  void finish(const StageContext& c)
  {
    // albedo and emission: uploaded by the photon stage, which every change of them re-runs
    const bool newCaustics = gatherRan && causticCount;
    std::vector<Vec3f> fronts(newCaustics ? mesh.vertexCount : 0);
    done.run(c.scene, c.options, mesh, direct.direct.data(), gathered.data(), pathScene.albedo.data(),
      c.scene.emission.empty() ? nullptr : pathScene.emission.data(), c.solution,
      newCaustics ? std::initializer_list<cuda::DeviceFinish::Extra>{ { caustics.data(),
                      fronts.size() * sizeof(Vec3f), fronts.data() } }
                  : std::initializer_list<cuda::DeviceFinish::Extra>{},
      stream);
    if (lightPending)
    {
      lightRays = device.counters[kLightSlot];
      lightPending = false;
    }
    if (gatherRan)
    {
      // Caustics per element: the fronts' (backs get none), or none without caustic photons.
      causticsHost = std::move(fronts);
      if (newCaustics)
      {
        causticsHost.resize(c.solution.direct.size(), Vec3f(0.f));
      }
      gatherRan = false;
    }
    c.solution.caustics = causticsHost;
  }

  /// counters' slots (pinned): the direct light's shadow rays, the paths' hits found, the
  /// photons and the caustic photons stored.
  static constexpr int kLightSlot = 0, kFoundSlot = 1, kPhotonSlot = 2, kCausticSlot = 3, kSlots = 4;

  cuda::DeviceContext device{ kSlots };
  cudaStream_t stream = device.stream;
  cuda::DeviceMesh mesh;
  /// The mesh's BVH for checks of a result (sceneTracer).
  std::unique_ptr<RayTracer> meshTracer = cuda::traceThrough(mesh.bvh, device.device, stream);
  cuda::DeviceDirectLight direct;
  cuda::DeviceFinish done;
  GPUBuffer<float> areas;
  paths::gpu::DevicePathScene pathScene;
  paths::PathScene pathView; ///< the photon stage's, over the device's arrays
  paths::gpu::DevicePaths paths;
  GPUBuffer<paths::Vpl> hits;
  GPUBuffer<std::uint32_t> subsetOffsets;
  GPUBuffer<float> subsetScale;
  gpu::DevicePhotons photons;
  GPUBuffer<Index> flags;
  GPUBuffer<Offset> scan;
  GPUBuffer<unsigned char> temp;
  gpu::DevicePointTree photonTree, siteTree, causticTree;
  /// The surface's pieces the estimates measure their discs by (SurfaceView).
  GPUBuffer<Vec3f> pieceCentroids, pieceCorners, pieceNormals;
  GPUBuffer<float> pieceAreas, pieceRadii;
  float pieceReach = 0.f;
  gpu::DevicePointTree pieceTree;
  gpu::DevicePhotons sorted, sites; ///< the photons and the estimates in their trees' orders
  GPUBuffer<Vec3f> sitePositions, siteNormals, siteRadiance;
  GPUBuffer<float> siteRadius2, treeRadius2; ///< the estimates' discs, in site and in site-tree order
  PointTreeView siteView;
  std::uint32_t siteCount = 0;
  GPUBuffer<Index> samples, neighbours;
  GPUBuffer<Vec3f> directions, sampleIrradiance, caustics;
  GPUBuffer<float> harmonicDistance;
  GPUBuffer<cuda::Rgba> gathered;
  std::vector<Vec3f> causticsHost;
  std::size_t photonCount = 0, causticCount = 0, clusterCount = 0;
  float estimateMax2 = 0.f; ///< kEstimateRadius, squared
  std::uint64_t gatherRays = 0, lightRays = 0;
  bool lightPending = false, gatherRan = false;
};
}

std::unique_ptr<MethodBackend> createCudaBackend(const SolverOptions&)
{
  return std::make_unique<PmCuda>();
}

void buildTreeOnDevice(const std::vector<Vec3f>& points, std::vector<Index>& order, std::vector<std::uint8_t>& axes)
{
  cuda::useFirstDevice();
  GPUBuffer<Vec3f> device;
  device.upload(points);
  gpu::DevicePointTree tree;
  tree.build(device.data(), std::uint32_t(points.size()), nullptr);
  LINKGI_CUDA_CHECK(cudaDeviceSynchronize());
  const PointTreeView view = tree.view();
  order.resize(points.size());
  axes.resize(points.size());
  LINKGI_CUDA_CHECK(cudaMemcpy(order.data(), view.order, order.size() * sizeof(Index), cudaMemcpyDeviceToHost));
  LINKGI_CUDA_CHECK(cudaMemcpy(axes.data(), view.axes, axes.size(), cudaMemcpyDeviceToHost));
}
}
