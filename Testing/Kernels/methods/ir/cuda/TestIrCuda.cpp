// Instant radiosity's device-side set-up against the host's: the VPL packing (ir::packVpls)
// and the visibility proxy (ir::buildProxy) built on the GPU must give what the host builds,
// and whole updates with interleaving and the proxy must agree between the backends.
#include "CudaFixtures.h"
#include "SceneFixtures.h"

#include "methods/ir/cuda/IrKernels.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Primitives.h"

#include "linkgi/Scenes.h"

#include <algorithm>
#include <array>
#include <tuple>

using namespace linkgi;
using cuda::GPUBuffer;
using ir::Vpl;

namespace
{
SolverOptions proxyOptions(std::uint32_t vpls, std::uint32_t interleave, std::uint32_t resolution)
{
  SolverOptions o;
  o.method = Method::InstantRadiosity;
  o.instantRadiosity.vplCount = vpls;
  o.instantRadiosity.interleave = interleave;
  o.instantRadiosity.proxyVisibility = resolution > 0;
  o.instantRadiosity.proxyResolution = std::max(2u, resolution);
  return o;
}

using Corners = std::array<std::tuple<float, float, float>, 3>;

/// A proxy as a sorted list of triangles by their corners' positions (each triangle's
/// corners sorted): what the shadow rays see, whatever the numbering.
std::vector<Corners> cornerSets(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles)
{
  std::vector<Corners> out;
  for (const Triangle& t : triangles)
  {
    Corners c;
    for (int k = 0; k < 3; ++k)
    {
      const Vec3f& p = positions[t.v[k]];
      c[k] = { p.x, p.y, p.z };
    }
    std::sort(c.begin(), c.end());
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}
}

TEST(IrCuda, DevicePackingIsTheHostPacking)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  // 37 paths of up to 4 VPLs (some none), in 1, 5 and 64 (more than paths) subsets.
  const std::uint32_t paths = 37, slotsPerPath = 4;
  std::vector<Vpl> slots(paths * slotsPerPath);
  std::vector<int> counts(paths);
  std::vector<Index> deviceCounts(paths + 1, 0);
  for (std::uint32_t p = 0; p < paths; ++p)
  {
    counts[p] = int((p * 7 + 3) % 5); // 0 to slotsPerPath
    deviceCounts[p] = Index(counts[p]);
    for (std::uint32_t k = 0; k < slotsPerPath; ++k)
    {
      Vpl& v = slots[p * slotsPerPath + k];
      v.position = Vec3f(float(p), float(k), 1.f);
      v.normal = Vec3f(0.f, 0.f, 1.f);
      v.flux = Vec3f(float(p * slotsPerPath + k));
      v.sky = k & 1;
    }
  }
  GPUBuffer<Vpl> deviceSlots;
  GPUBuffer<Index> countBuffer;
  GPUBuffer<Offset> offsets(paths + 1);
  GPUBuffer<unsigned char> temp;
  deviceSlots.upload(slots);
  countBuffer.upload(deviceCounts);
  cuda::exclusiveSum(countBuffer.data(), offsets.data(), paths + 1, temp, nullptr);
  for (std::uint32_t subsets : { 1u, 5u, 64u })
  {
    const ir::VplSet host = ir::packVpls(slots, counts, slotsPerPath, subsets);
    const std::uint32_t used = std::max(1u, std::min(subsets, paths));
    ASSERT_EQ(host.subsetScale.size(), used);
    GPUBuffer<Vpl> vpls(host.count());
    GPUBuffer<std::uint32_t> subsetOffsets(used + 1);
    GPUBuffer<float> subsetScale(used);
    ir::gpu::packVpls(deviceSlots.data(), countBuffer.data(), offsets.data(), paths, slotsPerPath, used,
      vpls.data(), subsetOffsets.data(), subsetScale.data(), nullptr);
    LINKGI_CUDA_CHECK(cudaDeviceSynchronize());
    EXPECT_EQ(subsetOffsets.download(), host.subsetOffsets) << subsets << " subsets";
    EXPECT_EQ(subsetScale.download(), host.subsetScale) << subsets << " subsets";
    const std::vector<Vpl> packed = vpls.download();
    ASSERT_EQ(packed.size(), host.vpls.size());
    for (std::size_t i = 0; i < packed.size(); ++i)
    {
      EXPECT_EQ(packed[i].position, host.vpls[i].position) << "VPL " << i;
      EXPECT_EQ(packed[i].flux, host.vpls[i].flux) << "VPL " << i;
      EXPECT_EQ(packed[i].sky, host.vpls[i].sky) << "VPL " << i;
    }
  }
}

TEST(IrCuda, DeviceProxyIsTheHostProxy)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  for (const char* name : { "cornell", "torso" })
  {
    Scene s = makeStandardScene(name);
    validateScene(s);
    GPUBuffer<Vec3f> positions;
    GPUBuffer<Triangle> triangles;
    positions.upload(s.positions);
    triangles.upload(s.triangles);
    for (std::uint32_t resolution : { 4u, 16u, 64u })
    {
      const ir::Proxy host = ir::buildProxy(s, resolution);
      const ir::ProxyGrid grid = ir::proxyGrid(sceneExtent(s), resolution);
      ASSERT_TRUE(ir::gpu::DeviceProxy::fits(grid, s.vertexCount()));
      ir::gpu::DeviceProxy device;
      device.build(grid, positions.data(), Index(s.vertexCount()), triangles.data(), Index(s.triangleCount()), nullptr);
      ASSERT_EQ(device.positionCount, host.positions.size()) << name << " at " << resolution;
      ASSERT_EQ(device.triangleCount, host.triangles.size()) << name << " at " << resolution;
      EXPECT_GT(device.triangleCount, 0u);
      EXPECT_EQ(grid.margin(), host.margin);
      std::vector<Vec3f> p(device.positionCount);
      std::vector<Triangle> t(device.triangleCount);
      device.positions.download(p.data(), p.size());
      device.triangles.download(t.data(), t.size());
      // The same clusters at the same means (summed in the same order) and the same triangles.
      EXPECT_EQ(cornerSets(p, t), cornerSets(host.positions, host.triangles)) << name << " at " << resolution;
    }
  }
}

TEST(IrCuda, BackendsAgreeWithInterleavingAndTheProxy)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  // The torso, straight, with its light moved, then bent (the proxy rebuilt on the GPU):
  // each backend with its own light paths, subsets and proxy.
  Scene straight = makeStandardScene("torso"), moved = straight;
  moved.lights[0].position.x += 0.1f;
  SceneParams bend;
  bend.deformation = 0.5f;
  Scene bent = makeStandardScene("torso", bend);
  bent.lights = moved.lights;
  const SolverOptions o = proxyOptions(1024, 4, 16);
  Solver cpu, gpu;
  int step = 0;
  for (const Scene* now : { &straight, &moved, &bent })
  {
    const Solution a = cpu.update(*now, test::onBackend(Backend::Cpu, o));
    const Solution& b = gpu.update(*now, test::onBackend(Backend::Cuda, o));
    ASSERT_EQ(gpu.stats().backend, "cuda") << gpu.stats().backendNote;
    EXPECT_LT(test::relativeError(b.direct, a.direct), 0.01f) << "step " << step;
    EXPECT_LT(test::relativeError(b.indirect, a.indirect), 0.02f) << "step " << step;
    EXPECT_LT(test::relativeError(b.radiance, a.radiance), 0.02f) << "step " << step;
    EXPECT_EQ(gpu.stats().counter("Vpls"), cpu.stats().counter("Vpls")) << "step " << step;
    EXPECT_GT(gpu.stats().rays, 0u) << "step " << step;
    EXPECT_GT(gpu.stats().lightRays, 0u) << "step " << step;
    ++step;
  }
}
