// The CUDA backend on small scenes: the GPU tracer against the CPU's, agreement of the two
// backends per stage option, caching, determinism, multi-GPU and the CPU fallback. Every
// test that needs a GPU skips (with the reason) where there is none.
#include "CudaFixtures.h"
#include "SceneFixtures.h"

#include "shared/BvhBuild.h"
#include "linkgi/Scenes.h"

#include <cmath>
#include <cstdlib>
#include <random>

using namespace linkgi;
using namespace linkgi::test;

namespace
{
SolverOptions fast()
{
  SolverOptions o;
  o.raysPerVertex = 64;
  return o;
}

void expectIdentical(const Solution& a, const Solution& b)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (std::size_t i = 0; i < a.elementCount(); ++i)
  {
    ASSERT_EQ(a.direct[i], b.direct[i]) << i;
    ASSERT_EQ(a.indirect[i], b.indirect[i]) << i;
    ASSERT_EQ(a.radiance[i], b.radiance[i]) << i;
  }
}
}

TEST(Cuda, RequestWithoutDeviceFallsBackToTheCpu)
{
  std::string why;
  if (!cuda::devices(&why).empty())
  {
    GTEST_SKIP() << "this machine has a CUDA device";
  }
  Solver solver;
  solver.update(roomWithBlock(), onBackend(Backend::Cuda, fast()));
  EXPECT_EQ(solver.stats().backend, "cpu");
  ASSERT_FALSE(solver.stats().warnings.empty());
  EXPECT_NE(solver.stats().warnings.back().find("CUDA backend not available"), std::string::npos);
  // Auto says why it chose the CPU, without a warning.
  Solver automatic;
  automatic.update(roomWithBlock(), onBackend(Backend::Auto, fast()));
  EXPECT_EQ(automatic.stats().backend, "cpu");
  EXPECT_NE(automatic.stats().backendNote.find("Auto"), std::string::npos);
  EXPECT_TRUE(automatic.stats().warnings.empty());
}

TEST(Cuda, GpuTracerFindsTheHostBvhHits)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const Scene s = makeStandardScene("tearoom");
  auto gpu = cuda::createRayTracer(0);
  auto cpu = createBvhRayTracer();
  gpu->build(s.positions, s.triangles);
  cpu->build(s.positions, s.triangles);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Ray> rays(20000);
  for (Ray& r : rays)
  {
    r.origin = s.positions[rng() % s.vertexCount()] + Vec3f(u(rng), u(rng), u(rng)) * 0.01f;
    r.direction = normalize(Vec3f(u(rng), u(rng), u(rng)));
  }
  std::vector<Hit> a(rays.size()), b(rays.size());
  gpu->trace(rays.data(), a.data(), rays.size());
  cpu->trace(rays.data(), b.data(), rays.size());
  std::vector<std::uint8_t> oa(rays.size()), ob(rays.size());
  gpu->occluded(rays.data(), oa.data(), rays.size());
  cpu->occluded(rays.data(), ob.data(), rays.size());
  std::size_t differ = 0, occludedDiffer = 0;
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    differ += a[i].triangle != b[i].triangle && std::fabs(a[i].t - b[i].t) > 1e-4f;
    occludedDiffer += oa[i] != ob[i];
  }
  EXPECT_LE(differ, rays.size() / 1000);
  EXPECT_LE(occludedDiffer, rays.size() / 1000);
}

TEST(Cuda, BackendsAgreeOnARoom)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  expectBackendsAgree(roomWithBlock(), fast(), 2e-3f);
}

TEST(Cuda, BackendsAgreeTwoSidedWithAnEnvironmentMap)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  Scene s = twoSquares(false, 12);
  s.environment.color = Vec3f(1.f);
  s.environment.width = 8;
  s.environment.height = 4;
  for (int i = 0; i < 32; ++i)
  {
    s.environment.texels.push_back(Vec3f(0.1f * (i % 8), 0.2f, 0.05f * (i / 8)));
  }
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3f(0.3f, -0.2f, -1.f));
  s.lights.push_back(sun);
  SolverOptions o = fast();
  o.twoSided = true;
  expectBackendsAgree(s, o, 2e-3f);
}

TEST(Cuda, ManyRaysPerVertexUseTheWideMerge)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  SolverOptions o = fast();
  o.raysPerVertex = 1024; // 4 rays per thread in the merge
  expectBackendsAgree(roomWithBlock(0.5f), o, 2e-3f);
  o.raysPerVertex = 100; // not a multiple of the warp: warps straddle elements
  expectBackendsAgree(roomWithBlock(0.5f), o, 2e-3f);
}

TEST(Cuda, TooManyRaysFallBackToTheCpuWithAWarning)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  SolverOptions o = onBackend(Backend::Cuda, fast());
  o.raysPerVertex = 2025;
  Solver solver;
  solver.update(twoSquares(true, 2), o);
  EXPECT_EQ(solver.stats().backend, "cpu");
  ASSERT_FALSE(solver.stats().warnings.empty());
  EXPECT_NE(solver.stats().warnings.back().find("CUDA backend failed"), std::string::npos);
}

TEST(Cuda, ResultsAreDeterministicAndCachedStagesMatchFreshSolves)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  Scene s = roomWithBlock();
  const SolverOptions o = onBackend(Backend::Cuda, fast());
  Solver a, b;
  expectIdentical(a.update(s, o), b.update(s, o));
  s.lights[0].position = { -0.7f, 2.2f, 0.1f };
  const Solution moved = a.update(s, o);
  EXPECT_FALSE(a.stats().ran("Links"));
  EXPECT_TRUE(a.stats().ran("LightLinks"));
  Solver fresh;
  expectIdentical(moved, fresh.update(s, o));
  for (Vec3f& albedo : s.albedo)
  {
    albedo = albedo * 0.5f;
  }
  const Solution recoloured = a.update(s, o);
  EXPECT_FALSE(a.stats().ran("LightLinks"));
  Solver fresh2;
  expectIdentical(recoloured, fresh2.update(s, o));
}

TEST(Cuda, DeformationRefitsOrRebuildsAndAgreesWithTheCpu)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const Scene rest = makeStandardScene("torso");
  SceneParams p;
  p.deformation = 0.7f;
  const Scene bent = makeStandardScene("torso", p);
  for (CudaBvhUpdate mode : { CudaBvhUpdate::Rebuild, CudaBvhUpdate::Refit })
  {
    SolverOptions o = onBackend(Backend::Cuda, fast());
    o.cudaBvhUpdate = mode;
    Solver gpu;
    gpu.update(rest, o);
    const Solution& moved = gpu.update(bent, o);
    EXPECT_EQ(gpu.stats().refitBvh, mode == CudaBvhUpdate::Refit);
    EXPECT_EQ(gpu.stats().builtBvh, mode == CudaBvhUpdate::Rebuild);
    Solver cpu;
    const Solution& reference = cpu.update(bent, onBackend(Backend::Cpu, fast()));
    EXPECT_LE(relativeError(moved.radiance, reference.radiance), 2e-3f);
  }
}

TEST(Cuda, AutoBvhUpdateRefitsSmallAndRebuildsLargeDeformations)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  Scene s = roomWithBlock();
  const SolverOptions o = onBackend(Backend::Cuda, fast()); // CudaBvhUpdate::Auto
  Solver solver;
  solver.update(s, o);
  for (Vec3f& p : s.positions)
  {
    p.y *= 1.05f; // boxes stay tight
  }
  solver.update(s, o);
  EXPECT_TRUE(solver.stats().refitBvh);
  for (Vec3f& p : s.positions)
  {
    // A strong twist about the vertical axis: a refit tree's boxes would swell.
    const float a = 2.5f * p.y, c = std::cos(a), sn = std::sin(a);
    p = Vec3f(c * p.x - sn * p.z, p.y, sn * p.x + c * p.z);
  }
  const Solution& twisted = solver.update(s, o);
  EXPECT_TRUE(solver.stats().builtBvh);
  Solver fresh;
  expectIdentical(twisted, fresh.update(s, o));
}

TEST(Cuda, HostSahTreeTracesLikeTheGpuTree)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const Scene s = makeStandardScene("tearoom");
  SolverOptions sah = onBackend(Backend::Cuda, fast()), lbvh = sah;
  sah.cudaBvhBuild = CudaBvhBuild::HostSah;
  Solver a, b;
  const Solution& x = a.update(s, sah);
  const Solution& y = b.update(s, lbvh);
  EXPECT_LE(relativeError(x.radiance, y.radiance), 1e-3f);
  EXPECT_NEAR(double(a.stats().counter("LinksCompressed")), double(b.stats().counter("LinksCompressed")),
    1e-4 * b.stats().counter("LinksCompressed"));
}

TEST(Cuda, AllGpusGiveTheSameLinksAsOne)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  if (cuda::devices().size() < 2)
  {
    GTEST_SKIP() << "needs two CUDA devices";
  }
  const Scene s = makeStandardScene("tearoom");
  SolverOptions one = onBackend(Backend::Cuda, fast()), all = one;
  one.cudaDevices = 1;
  all.cudaDevices = 0;
  Solver a, b;
  const Solution& single = a.update(s, one);
  const Solution& multi = b.update(s, all);
  ASSERT_GE(b.stats().devices, 2);
  std::uint64_t linked = 0;
  for (std::uint64_t n : b.stats().linkedPerDevice)
  {
    EXPECT_GT(n, 0u);
    linked += n;
  }
  EXPECT_EQ(linked, s.vertexCount());
  EXPECT_EQ(a.stats().counter("LinksCompressed"), b.stats().counter("LinksCompressed"));
  expectIdentical(single, multi);
}

namespace
{
/// Each output of a within `tolerance` of b's, relative to the element's value.
void expectClose(const Solution& a, const Solution& b, float tolerance)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (const auto member : { &Solution::direct, &Solution::indirect, &Solution::radiance })
  {
    const std::vector<Vec3f>&x = a.*member, &y = b.*member;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(x[i][c], y[i][c], tolerance * std::fabs(y[i][c]) + 1e-7f) << i;
      }
    }
  }
}

/// An environment variable (a testing knob of the engine) while it lives.
struct Knob
{
  Knob(const char* name, int value) : name(name) { setenv(name, std::to_string(value).c_str(), 1); }
  ~Knob() { unsetenv(name); }
  const char* name;
};

/// LINKGI_CUDA_PARTITIONS while it lives.
struct Partitions : Knob
{
  explicit Partitions(int p) : Knob("LINKGI_CUDA_PARTITIONS", p) {}
};
}

// Several GPUs keep the rows they linked and exchange the radiance between bounces; P
// partitions on one GPU take the same paths (peer copies, gathers to the first).
TEST(Cuda, PartitionsOnOneGpuGiveTheOneGpuSolution)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  // Several batches, so several blocks of rows, per partition (batches of at most 1000).
  const Knob batches("LINKGI_CUDA_MAX_BATCH", 1000);
  Scene room = makeStandardScene("tearoom");
  Scene twoSided = twoSquares(false, 40);
  twoSided.environment.color = Vec3f(0.6f, 0.7f, 0.9f);
  Light lamp;
  lamp.position = Vec3f(0.4f, 0.6f, 0.5f);
  twoSided.lights.push_back(lamp);
  SolverOptions o = onBackend(Backend::Cuda, fast());
  o.cudaDevices = 1; // the partitions share the first GPU, however many the machine has
  for (Scene* s : { &room, &twoSided })
  {
    o.twoSided = s == &twoSided;
    const std::size_t elements = o.twoSided ? 2 * s->vertexCount() : s->vertexCount();
    Solver one;
    const Solution single = one.update(*s, o);
    ASSERT_EQ(one.stats().linkedPerDevice.size(), 1u);
    for (int p : { 2, 3 })
    {
      const Partitions partitions(p);
      Solver many;
      const Solution split = many.update(*s, o);
      ASSERT_EQ(many.stats().backend, "cuda") << many.stats().backendNote;
      // Each partition holds the rows it linked, and only those.
      ASSERT_EQ(many.stats().linkedPerDevice.size(), std::size_t(p));
      std::uint64_t rows = 0;
      int holding = 0;
      for (std::uint64_t n : many.stats().linkedPerDevice)
      {
        EXPECT_LT(n, elements);
        holding += n > 0;
        rows += n;
      }
      EXPECT_EQ(rows, elements);
      EXPECT_GE(holding, 2);
      for (std::uint32_t batches : many.stats().batchesPerDevice)
      {
        EXPECT_GT(batches, 1u) << "batches of at most 1000 elements";
      }
      EXPECT_EQ(many.stats().counter("LinksCompressed"), one.stats().counter("LinksCompressed"));
      expectClose(split, single, 1e-5f);
      // A light-only update reuses the partitions' rows.
      Scene moved = *s;
      for (Light& l : moved.lights)
      {
        l.position += Vec3f(0.05f, 0.f, 0.02f);
      }
      Solver oneMoved;
      const Solution reference = oneMoved.update(moved, o);
      const Solution& movedSplit = many.update(moved, o);
      EXPECT_FALSE(many.stats().ran("Links"));
      expectClose(movedSplit, reference, 1e-5f);
    }
  }
}

TEST(Cuda, PartitionsTakeOneRangeEachOnTheNextRelink)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  // The first link stage measures (batches sized by speed); a relink of the same elements
  // then gives each partition one contiguous range of equal cost. The solution stays the
  // one-partition one.
  const Scene room = makeStandardScene("tearoom");
  Scene moved = room;
  for (Vec3f& p : moved.positions)
  {
    p.y *= 1.01f;
  }
  SolverOptions o = onBackend(Backend::Cuda, fast());
  o.cudaDevices = 1;
  Solver one;
  const Solution single = one.update(moved, o);
  const Partitions partitions(3);
  Solver many;
  many.update(room, o);
  const Solution& split = many.update(moved, o);
  ASSERT_TRUE(many.stats().ran("Links"));
  ASSERT_EQ(many.stats().batchesPerDevice.size(), 3u);
  std::uint64_t rows = 0;
  for (std::size_t d = 0; d < 3; ++d)
  {
    EXPECT_EQ(many.stats().batchesPerDevice[d], 1u) << "partition " << d;
    EXPECT_GT(many.stats().linkedPerDevice[d], 0u) << "partition " << d;
    rows += many.stats().linkedPerDevice[d];
  }
  EXPECT_EQ(rows, moved.vertexCount());
  EXPECT_EQ(many.stats().counter("LinksCompressed"), one.stats().counter("LinksCompressed"));
  expectClose(split, single, 1e-5f);
}

TEST(Cuda, GpuMemoryIsWhatTheEngineAllocated)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  Solver solver;
  solver.update(roomWithBlock(), onBackend(Backend::Cuda, fast()));
  const SolverStats& st = solver.stats();
  ASSERT_EQ(st.backend, "cuda");
  // At least the link matrices, far below a whole device (the context alone is ~0.5 GB).
  EXPECT_GE(st.gpuBytesAllocated, st.counter("LinkBytes"));
  EXPECT_LT(st.gpuBytesAllocated, std::uint64_t(256) << 20);
}
