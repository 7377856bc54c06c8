// Instant radiosity on one GPU: the proxy, the VPLs and the gather stay on the device; the
// mesh and its BVH, the light paths' scene, the direct light and the finish (smoothing,
// radiance) are the pieces every one-GPU backend shares (cuda/OneDevice.h, ir/IrKernels.h's
// DevicePathScene). The host builds the source table; the
// device packs the VPL set in the layout of the CPU's packVpls and clusters the proxy as the
// CPU's buildProxy does. One stream: an update waits for the device where the host needs a
// number (the VPLs found, the proxy's size) and once at the end, for the output.
#include "methods/ir/IrBackends.h"
#include "methods/ir/cuda/IrKernels.h"

#include "cuda/OneDevice.h"
#include "cuda/GPUBuffer.h"
#include "cuda/PinnedStaging.h"
#include "cuda/Primitives.h"

#include "cuda/Cuda.h"

#include <array>
#include <cmath>

namespace linkgi::ir
{
namespace
{
using namespace engine;
using cuda::DeviceMesh;
using cuda::GPUBuffer;
using cuda::Rgba;

/// A VPL set on the GPU.
struct DeviceVpls
{
  GPUBuffer<Vpl> vpls;
  GPUBuffer<std::uint32_t> subsetOffsets;
  GPUBuffer<float> subsetScale;
  std::size_t count = 0, subsets = 0;

  /// Packs the light paths' VPLs (ir::gpu::packVpls); `total`: the VPLs found.
  void pack(const GPUBuffer<Vpl>& slots, const GPUBuffer<Index>& counts, const GPUBuffer<Offset>& pathOffsets,
    std::uint32_t paths, std::uint32_t slotsPerPath, std::uint32_t interleave, std::size_t total,
    cudaStream_t stream)
  {
    subsets = std::max(1u, std::min(interleave, paths));
    vpls.resize(std::max<std::size_t>(total, 1));
    subsetOffsets.resize(subsets + 1);
    subsetScale.resize(subsets);
    gpu::packVpls(slots.data(), counts.data(), pathOffsets.data(), paths, slotsPerPath, std::uint32_t(subsets),
      vpls.data(), subsetOffsets.data(), subsetScale.data(), stream);
    count = total;
  }

  void upload(const VplSet& set, cudaStream_t stream)
  {
    vpls.upload(set.vpls, stream);
    subsetOffsets.upload(set.subsetOffsets, stream);
    subsetScale.upload(set.subsetScale, stream);
    count = set.count();
    subsets = set.subsetScale.size();
  }
};

gpu::GatherLaunch gatherLaunch(const DeviceMesh& mesh, const DeviceVpls& vpls, BvhView visibility,
  const GatherParams& params, bool twoSided)
{
  gpu::GatherLaunch g;
  g.visibility = visibility;
  g.positions = mesh.positions.data();
  g.normals = mesh.normals.data();
  g.origins = mesh.origins.data();
  g.vertexCount = mesh.vertexCount;
  g.twoSided = twoSided;
  g.vpls = vpls.vpls.data();
  g.subsetOffsets = vpls.subsetOffsets.data();
  g.subsetScale = vpls.subsetScale.data();
  g.params = params;
  g.params.subsets = std::uint32_t(vpls.subsets);
  return g;
}

class IrCuda final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    // Device state is updated in place: a failed update leaves it unusable (discard()).
    switch (stage)
    {
      case kGeometryStage:
        return mesh.update(c.scene, c.changes, stream, &c.stats);
      case kProxyStage:
        return buildProxyBvh(c);
      case kVplStage:
        return traceVpls(c);
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
    st.setCounter("Vpls", vpls.count);
  }

  const RayTracer* sceneTracer() const override { return meshTracer.get(); }

private:
  void buildProxyBvh(const StageContext& c)
  {
    proxyMargin = 0.f;
    proxyTriangles = 0;
    if (!c.options.instantRadiosity.proxyVisibility)
    {
      return;
    }
    const ProxyGrid grid = proxyGrid(mesh.extent, c.options.instantRadiosity.proxyResolution);
    proxyMargin = grid.margin();
    if (gpu::DeviceProxy::fits(grid, mesh.vertexCount))
    {
      proxy.build(grid, mesh.positions.data(), mesh.vertexCount, mesh.triangles.data(), mesh.triangleCount, stream);
    }
    else
    {
      // Too many clusters for the device's sort keys: the host's clustering, uploaded.
      const Proxy host = buildProxy(c.scene, grid.resolution);
      proxy.positions.upload(host.positions, stream);
      proxy.triangles.upload(host.triangles, stream);
      proxy.positionCount = Index(host.positions.size());
      proxy.triangleCount = Index(host.triangles.size());
    }
    proxyTriangles = proxy.triangleCount;
    if (proxyTriangles)
    {
      proxyBvh.build(proxy.positions.data(), proxy.positionCount, proxy.triangles.data(), proxyTriangles, stream);
    }
  }

  void traceVpls(const StageContext& c)
  {
    const Scene& s = c.scene;
    PathSetup setup = buildPathSetup(s, {}, {}, c.options, &mesh.extent);
    // Instant radiosity lights mirrors and glass as diffuse surfaces (warned).
    PathScene view = pathScene.upload(s, setup, c.changes, mesh, false, stream);
    const std::size_t found = gpu::traceAllPaths(view, mesh.bvh.view(), setup.targetVpls, paths,
      rayCounts + kFoundSlot, stream);
    vpls.pack(paths.slots, paths.counts, paths.pathOffsets, view.paths, view.bounces + 1,
      c.options.instantRadiosity.interleave, found, stream);
  }

  void directLight(const StageContext& c)
  {
    direct.queue(c.scene, c.options, mesh, rayCounts + kLightSlot, stream);
    lightPending = true;
  }

  void gather(const StageContext& c)
  {
    const Elements elements{ c.scene.vertexCount(), c.options.twoSided };
    GatherParams gp;
    gp.dmin = c.options.instantRadiosity.clampDistance * mesh.extent.diagonal;
    gp.proxyMargin = c.options.instantRadiosity.proxyVisibility ? proxyMargin : 0.f;
    gp.seed = c.options.seed;
    const BvhView visibility = gp.proxyMargin > 0.f
      ? (proxyTriangles ? proxyBvh.view() : BvhView{})
      : mesh.bvh.view();
    gathered.resize(elements.count());
    gatherCounter.resize(1);
    gatherCounter.fillZero(stream);
    gpu::GatherLaunch launch = gatherLaunch(mesh, vpls, visibility, gp, c.options.twoSided);
    if (launch.params.subsets > 1)
    {
      // The order depends on the vertex count, the sides, the subsets and the seed only.
      const std::array<std::uint64_t, 4> key = { mesh.vertexCount, c.options.twoSided, launch.params.subsets, gp.seed };
      if (key != orderKey)
      {
        gpu::elementsBySubset(mesh.vertexCount, c.options.twoSided, launch.params.subsets, gp.seed, orderKeys, orderIds,
          orderTemp, elementOrder, stream);
        orderKey = key;
      }
      launch.order = elementOrder.data();
    }
    gpu::gatherVpls(launch, gathered.data(), gatherCounter.data(), stream);
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(rayCounts + kGatherSlot, gatherCounter.data(), sizeof(unsigned long long),
      cudaMemcpyDeviceToHost, stream));
    gatherPending = true;
  }

  void finish(const StageContext& c)
  {
    // albedo and emission: uploaded by the VPL stage, which every change of them re-runs
    const Vec3f* emission = c.scene.emission.empty() ? nullptr : pathScene.emission.data();
    const Rgba* indirect = gathered.data();
    if (c.options.instantRadiosity.compensationRays > 0)
    {
      gpu::CompensationLaunch p;
      p.mesh = mesh.bvh.view();
      p.inputs.positions = mesh.positions.data();
      p.inputs.normals = mesh.normals.data();
      p.inputs.origins = mesh.origins.data();
      p.inputs.triangles = mesh.triangles.data();
      p.inputs.faceNormals = mesh.faceNormals.data();
      p.inputs.albedo = pathScene.albedo.data();
      p.inputs.emission = emission;
      p.inputs.direct = direct.direct.data();
      p.inputs.lights = direct.lights.data(); // the lights that emit
      p.inputs.lightCount = Index(direct.lights.size());
      p.inputs.vertexCount = mesh.vertexCount;
      p.inputs.twoSided = c.options.twoSided;
      p.inputs.dmin = c.options.instantRadiosity.clampDistance * mesh.extent.diagonal;
      p.indirect = gathered.data();
      p.side = squareSide(c.options.instantRadiosity.compensationRays);
      p.seed = c.options.seed;
      compensated.resize(gathered.size());
      gpu::compensate(p, compensated.data(), stream);
      indirect = compensated.data();
    }
    done.run(c.scene, c.options, mesh, direct.direct.data(), indirect, pathScene.albedo.data(), emission,
      c.solution, {}, stream);
    if (lightPending)
    {
      lightRays = rayCounts[kLightSlot];
      lightPending = false;
    }
    if (gatherPending)
    {
      gatherRays = rayCounts[kGatherSlot];
      gatherPending = false;
    }
  }

  /// The pinned counters' slots: the direct light's and the gather's shadow rays, the VPLs
  /// found.
  static constexpr int kLightSlot = 0, kGatherSlot = 1, kFoundSlot = 2;

  cuda::DeviceContext device{ kFoundSlot + 1 };
  cudaStream_t stream = device.stream;
  unsigned long long* rayCounts = device.counters;
  DeviceMesh mesh;
  /// The mesh's BVH for checks of a result (sceneTracer).
  std::unique_ptr<RayTracer> meshTracer = cuda::traceThrough(mesh.bvh, device.device, stream);
  cuda::DeviceDirectLight direct;
  cuda::DeviceFinish done;
  gpu::DeviceProxy proxy;
  cuda::DeviceBvh proxyBvh;
  Index proxyTriangles = 0;
  float proxyMargin = 0.f;
  gpu::DevicePathScene pathScene;
  gpu::DevicePaths paths;
  DeviceVpls vpls;
  GPUBuffer<Rgba> gathered;
  GPUBuffer<Rgba> compensated; ///< gathered plus the clamp's compensation (kept: equal sizes allocate nothing)
  GPUBuffer<unsigned long long> gatherCounter;
  GPUBuffer<Index> elementOrder, orderIds; ///< the gather's elements by subset, and scratch
  GPUBuffer<std::uint64_t> orderKeys;
  GPUBuffer<unsigned char> orderTemp;
  std::array<std::uint64_t, 4> orderKey{}; ///< what elementOrder was sorted for (0 subsets: none)
  bool lightPending = false, gatherPending = false;
  std::uint64_t gatherRays = 0, lightRays = 0;
};
}

std::unique_ptr<MethodBackend> createCudaBackend(const SolverOptions&)
{
  return std::make_unique<IrCuda>();
}

std::vector<Vec3f> gatherCuda(const Scene& scene, const VplSet& set, const GatherParams& params,
  bool twoSided)
{
  cuda::useFirstDevice();
  cudaStream_t stream = nullptr;
  DeviceMesh mesh;
  mesh.update(scene, kEverything, stream, nullptr);
  DeviceVpls vpls;
  vpls.upload(set, stream);
  const Elements elements{ scene.vertexCount(), twoSided };
  GPUBuffer<Rgba> out(elements.count());
  GPUBuffer<unsigned long long> rays(1);
  rays.fillZero(stream);
  gpu::GatherLaunch launch = gatherLaunch(mesh, vpls, mesh.bvh.view(), params, twoSided);
  GPUBuffer<Index> order, ids;
  GPUBuffer<std::uint64_t> keys;
  GPUBuffer<unsigned char> temp;
  if (launch.params.subsets > 1)
  {
    gpu::elementsBySubset(mesh.vertexCount, twoSided, launch.params.subsets, params.seed, keys, ids, temp, order, stream);
    launch.order = order.data();
  }
  gpu::gatherVpls(launch, out.data(), rays.data(), stream);
  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  const std::vector<Rgba> rgba = out.download();
  std::vector<Vec3f> result(rgba.size());
  for (std::size_t i = 0; i < rgba.size(); ++i)
  {
    result[i] = { rgba[i].r, rgba[i].g, rgba[i].b };
  }
  return result;
}
}
