// The memory budget: an update estimated to need more host memory than the budget
// is refused before anything is allocated, with an error that says what would fit, and the
// previous result stays; the estimate bounds the measured peak within a stated factor.
#include "SceneFixtures.h"

#include "engine/MemoryBudget.h"

#include "linkgi/Error.h"
#include "methods/links/Links.h"
#include "linkgi/Memory.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <malloc.h>
#include <iostream>

using namespace linkgi;

namespace
{
constexpr std::uint32_t kAllStages = ~0u;

/// The estimate from the sizes alone (the link method: its links at their bound).
std::uint64_t sizeEstimate(const Scene& s, const SolverOptions& o)
{
  return engine::methodSpec(o.method).estimateMemory(MemoryShape::of(s), o, kAllStages, false).hostBytes;
}

/// What a fresh solver's first update on the CPU estimates and, for the link method, what it
/// sampled to get there (`shape`).
std::uint64_t firstUpdateEstimate(const Scene& s, SolverOptions o, MemoryShape* shape = nullptr)
{
  o.backend = Backend::Cpu;
  o.memoryBudget = 0;
  Solver solver;
  solver.update(s, o);
  if (shape)
  {
    *shape = MemoryShape::of(s);
    shape->sampledPerElement = solver.stats().memorySampledPerElement;
  }
  return solver.stats().hostBytesEstimated;
}

/// The vertices that a fresh solver's refusal of `o` on `s` says would fit; a test failure
/// (and 0) where it is not refused.
std::uint64_t verticesThatFitOnRefusal(const Scene& s, const SolverOptions& o)
{
  try
  {
    Solver().update(s, o);
  }
  catch (const OutOfMemoryBudget& e)
  {
    return e.verticesThatFit();
  }
  ADD_FAILURE() << "not refused";
  return 0;
}

std::string refusal(Solver& solver, const Scene& s, const SolverOptions& o)
{
  try
  {
    solver.update(s, o);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}
}

TEST(TestMemoryBudget, OverBudgetIsRefusedAndThePreviousResultKept)
{
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 16;
  Solver solver;
  const Solution before = solver.update(s, o);
  const std::uint64_t linkBuildsBefore = solver.stats().runs("LinkBuilds");

  SolverOptions more = o;
  more.raysPerVertex = 256;
  more.memoryBudget = sizeEstimate(s, o) + 1; // what 16 rays need at most, not 256
  const std::string message = refusal(solver, s, more);
  EXPECT_NE(message.find("Not enough memory"), std::string::npos) << message;
  EXPECT_NE(message.find("(MemoryBudget)"), std::string::npos) << message;
  EXPECT_NE(message.find("256 rays per vertex"), std::string::npos) << message;
  EXPECT_NE(message.find("would fit"), std::string::npos) << message;
  std::cout << message << "\n";

  // The previous solution and its caches are whole: the same request costs nothing more.
  EXPECT_EQ(solver.solution().indirect, before.indirect);
  EXPECT_EQ(solver.solution().direct, before.direct);
  EXPECT_EQ(solver.stats().runs("LinkBuilds"), linkBuildsBefore);
  solver.update(s, o);
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_EQ(solver.solution().indirect, before.indirect);
}

TEST(TestMemoryBudget, WhatItSaysFitsDoesFit)
{
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  o.raysPerVertex = 256;
  const engine::MethodSpec& spec = engine::methodSpec(o.method);
  const MemoryShape shape = MemoryShape::of(s);
  const std::uint64_t budget = sizeEstimate(s, o) / 3;
  const engine::MemoryVerdict v = engine::judgeMemory(spec, shape, o, kAllStages, false, budget);
  ASSERT_FALSE(v.fits);
  ASSERT_GT(v.raysThatFit, 0u);
  ASSERT_LT(v.raysThatFit, o.raysPerVertex);
  SolverOptions fewer = o;
  fewer.raysPerVertex = v.raysThatFit;
  EXPECT_LE(spec.estimateMemory(shape, fewer, kAllStages, false).hostBytes, budget);
  const auto k = std::uint32_t(std::lround(std::sqrt(double(v.raysThatFit)))) + 1;
  fewer.raysPerVertex = k * k; // the next square up does not
  EXPECT_GT(spec.estimateMemory(shape, fewer, kAllStages, false).hostBytes, budget);

  ASSERT_GT(v.verticesThatFit, 0u);
  ASSERT_LT(v.verticesThatFit, shape.vertices);
  MemoryShape smaller = shape;
  smaller.vertices = v.verticesThatFit;
  smaller.triangles = shape.triangles * v.verticesThatFit / shape.vertices;
  EXPECT_LE(spec.estimateMemory(smaller, o, kAllStages, false).hostBytes, budget);
  smaller.vertices = v.verticesThatFit * 101 / 100;
  smaller.triangles = shape.triangles * smaller.vertices / shape.vertices;
  EXPECT_GT(spec.estimateMemory(smaller, o, kAllStages, false).hostBytes, budget);

  // And the solver accepts the advice under that budget.
  Solver solver;
  SolverOptions advised = o;
  advised.backend = Backend::Cpu;
  advised.memoryBudget = budget;
  advised.raysPerVertex = v.raysThatFit;
  EXPECT_NO_THROW(solver.update(s, advised));
  EXPECT_LE(solver.stats().hostBytesEstimated, budget);
  EXPECT_EQ(solver.stats().memoryBudget, budget);
}

TEST(TestMemoryBudget, ALightMoveNeedsNoLinkMemory)
{
  Scene s = test::roomWithBlock();
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 64;
  Solver solver;
  solver.update(s, o);
  // A budget below a full update's estimate: moving the light re-runs no link stage, so it
  // fits; asking for new links does not.
  const std::uint64_t full = solver.stats().hostBytesEstimated;
  ASSERT_EQ(full, firstUpdateEstimate(s, o));
  o.memoryBudget = full / 4;
  s.lights[0].position.x += 0.5f;
  EXPECT_NO_THROW(solver.update(s, o));
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_TRUE(solver.stats().ran("LightLinks"));
  EXPECT_LT(solver.stats().hostBytesEstimated, o.memoryBudget);
  o.seed = 7;
  EXPECT_NE(refusal(solver, s, o).find("Not enough memory"), std::string::npos);
}

TEST(TestMemoryBudget, AutomaticBudgetIsWhatIsAvailableLessAMargin)
{
  const std::uint64_t available = availableHostBytes();
  if (available == 0)
  {
    GTEST_SKIP() << "No /proc/meminfo on this system: no automatic budget.";
  }
  const std::uint64_t budget = hostMemoryBudget(0);
  EXPECT_LT(budget, available);
  EXPECT_GE(budget + (std::uint64_t(512) << 20), available - available / 10 - 1);
  EXPECT_EQ(hostMemoryBudget(12345), 12345u);

  // Under the automatic budget, a request far beyond the machine (a billion vertices'
  // worth of rays on a small mesh cannot be made, so ask the estimate directly).
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  MemoryShape huge = MemoryShape::of(s);
  huge.vertices *= 1000000;
  huge.triangles *= 1000000;
  const engine::MemoryVerdict v =
    engine::judgeMemory(engine::methodSpec(o.method), huge, o, kAllStages, false, budget);
  EXPECT_FALSE(v.fits);
  EXPECT_GT(v.verticesThatFit, 0u);
}

TEST(TestMemoryBudget, EstimateBoundsTheMeasuredPeak)
{
  // A fresh solver's first update: its peak resident set above what the process held
  // before, against the estimate (the links per row of a sample of rows, with a margin for
  // its error, here at their bound of 3 per ray: 64 rays in a closed room); the factor
  // below is what it may overstate by on this mesh: 1.15-1.22 on the 2-core VM (TBB,
  // Embree; 45.4-48.4 MiB measured, 55.6 estimated).
  constexpr double kMostOver = 2.5;
  const Scene s = test::roomWithBlock(0.06f);
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 64;
  // Memory that earlier tests freed but the allocator kept would be reused without raising
  // the resident set: give it back to the system first, so new pages are what is counted.
  malloc_trim(0);
  if (!resetPeakResident() || residentBytes() == 0)
  {
    GTEST_SKIP() << "The peak resident set cannot be reset or read here (/proc/self).";
  }
  const std::uint64_t before = residentBytes();
  std::uint64_t measured = 0, estimated = 0;
  {
    Solver solver;
    solver.update(s, o);
    measured = peakResidentBytes() - before;
    estimated = solver.stats().hostBytesEstimated;
  }
  RecordProperty("vertices", std::to_string(s.vertexCount()));
  RecordProperty("measured_peak_bytes", std::to_string(measured));
  RecordProperty("estimated_bytes", std::to_string(estimated));
  std::cout << s.vertexCount() << " vertices, 64 rays: measured peak " << formatBytes(measured)
            << ", estimated " << formatBytes(estimated) << "\n";
  EXPECT_GE(estimated, measured);
  EXPECT_LE(double(estimated), kMostOver * double(measured));
}

TEST(TestMemoryBudget, TheSampledRowsLinkAsTheWholeMeshDoes)
{
  // The link method estimates its links from every 64th row (at least 256) with a margin of
  // 10% (LinksCpu.cpp): on rooms, a model in no room and a lamp over a floor, the sample's
  // mean stays within that of the whole mesh's.
  for (const char* name : { "cornell", "torso", "tearoom", "colorlamp" })
  {
    const Scene s = makeStandardScene(name);
    SolverOptions o;
    o.backend = Backend::Cpu;
    Solver solver;
    solver.update(s, o);
    const double sampled = solver.stats().memorySampledPerElement;
    auto tracer = createCpuRayTracer();
    tracer->build(s.positions, s.triangles);
    const DetailNodes detail = detailNodes(s, detailNodeBudget(s.vertexCount()));
    const LinkOptions lo{ o.raysPerVertex, o.twoSided, o.twist, o.seed, nullptr, &detail };
    const LinkStructure all = buildLinks(s, rayOrigins(s, Topology::build(s.vertexCount(), s.triangles)), *tracer,
      frontFaceNormals(s), lo);
    const double whole = double(all.transport.nonZeros() + all.environment.nonZeros()) / double(s.vertexCount());
    std::cout << name << ": " << sampled << " links per sampled row, " << whole << " per row\n";
    EXPECT_NEAR(sampled / whole, 1.0, 0.1) << name;
  }
}

TEST(TestMemoryBudget, LinksBuiltElementByElementAreTheTwoPassLinks)
{
  // The CPU links are traced and compressed element by element (no buffer of every hit);
  // they must be the rows of tracing everything first, bit for bit.
  for (const bool twoSided : { false, true })
  {
    const Scene s = test::roomWithBlock();
    auto tracer = createCpuRayTracer();
    tracer->build(s.positions, s.triangles);
    const LinkOptions o{ 64, twoSided, true, 3 };
    const Topology topo = Topology::build(s.vertexCount(), s.triangles);
    const std::vector<RayOrigin> origins = rayOrigins(s, topo);
    const std::vector<Vec3f> faces = frontFaceNormals(s);
    const LinkStructure twoPass = compressLinks(s, traceLinkRays(s, origins, *tracer, o), faces, o);
    double msCompress = -1.0;
    const LinkStructure fused = buildLinks(s, origins, *tracer, faces, o, {}, &msCompress);
    EXPECT_GE(msCompress, 0.0);
    EXPECT_EQ(fused.rays, twoPass.rays);
    EXPECT_EQ(fused.rawLinks, twoPass.rawLinks);
    for (const auto& [a, b] : { std::make_pair(&fused.transport, &twoPass.transport),
           std::make_pair(&fused.environment, &twoPass.environment) })
    {
      EXPECT_EQ(a->rowOffsets, b->rowOffsets);
      EXPECT_EQ(a->columns, b->columns);
      EXPECT_EQ(a->weights, b->weights);
    }
  }
}

TEST(TestMemoryBudget, TheRefusalCarriesTheVerticesThatFit)
{
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  o.backend = Backend::Cpu;
  MemoryShape sampled;
  o.memoryBudget = firstUpdateEstimate(s, o, &sampled) / 2;
  ASSERT_GT(sampled.sampledPerElement, 0.0) << "the link method samples its rows";
  const engine::MemoryVerdict v =
    engine::judgeMemory(engine::methodSpec(o.method), sampled, o, kAllStages, false, o.memoryBudget);
  const std::uint64_t fit = verticesThatFitOnRefusal(s, o);
  EXPECT_EQ(fit, v.verticesThatFit);
  EXPECT_GT(fit, 0u);
  EXPECT_LT(fit, s.vertexCount());
}

namespace
{
/// Set in the environment of the child process that measures one method's first update:
/// the method, and the scene (a standard scene's name; unset: a room with a block).
constexpr const char* kMeasuredMethod = "LINKGI_MEASURED_METHOD";
constexpr const char* kMeasuredScene = "LINKGI_MEASURED_SCENE";

struct PeakAndEstimate
{
  double peak = 0.0, estimate = 0.0;
};

/// One method's first update on a room (or the standard scene `scene`), measured in a
/// process of its own (the test binary again, running the disabled test below): a process's
/// peak resident set only grows, and the first update is the one that also touches the
/// threads' stacks and arenas.
PeakAndEstimate measureInChild(Method method, const std::string& scene = {})
{
  const std::string command = std::string(kMeasuredMethod) + "=" + std::to_string(int(method)) +
    (scene.empty() ? "" : " " + std::string(kMeasuredScene) + "=" + scene) + " '" + std::filesystem::read_symlink("/proc/self/exe").string() + "' --gtest_also_run_disabled_tests"
    " --gtest_filter=TestMemoryBudget.DISABLED_FirstUpdateOfOneMethod 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  PeakAndEstimate out;
  if (!pipe)
  {
    return out;
  }
  char line[512];
  while (std::fgets(line, sizeof line, pipe))
  {
    std::sscanf(line, "peak %lf estimate %lf", &out.peak, &out.estimate);
  }
  pclose(pipe);
  return out;
}

/// Every method's first update on `scene` (as measureInChild) estimated within 1.3 of its
/// measured peak either way.
void expectEveryMethodEstimatesItsMeasuredPeak(const std::string& scene)
{
  if (!resetPeakResident() || residentBytes() == 0)
  {
    GTEST_SKIP() << "The peak resident set cannot be reset or read here (/proc/self).";
  }
  for (const Method method : { Method::Links, Method::InstantRadiosity, Method::ImplicitVisibility, Method::PhotonMapping })
  {
    const char* name = engine::methodSpec(method).name();
    const PeakAndEstimate m = measureInChild(method, scene);
    ASSERT_GT(m.peak, 0.0) << name << ": the child process reported nothing";
    const double ratio = m.estimate / m.peak;
    std::cout << name << ": measured peak " << formatBytes(std::uint64_t(m.peak)) << ", estimated "
              << formatBytes(std::uint64_t(m.estimate)) << " (" << ratio << "x)\n";
    EXPECT_GE(ratio, 1.0 / 1.3) << name;
    EXPECT_LE(ratio, 1.3) << name;
  }
}
}

TEST(TestMemoryBudget, DISABLED_FirstUpdateOfOneMethod)
{
  const char* method = std::getenv(kMeasuredMethod);
  ASSERT_NE(method, nullptr);
  const char* scene = std::getenv(kMeasuredScene);
  const Scene s = scene ? makeStandardScene(scene) : test::roomWithBlock(0.1f);
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.method = Method(std::atoi(method));
  malloc_trim(0);
  ASSERT_TRUE(resetPeakResident());
  const std::uint64_t before = residentBytes();
  Solver solver;
  solver.update(s, o);
  std::printf("peak %llu estimate %llu vertices %zu\n", (unsigned long long)(peakResidentBytes() - before),
    (unsigned long long)solver.stats().hostBytesEstimated, s.vertexCount());
}

TEST(TestMemoryBudget, EveryMethodEstimatesItsMeasuredPeak)
{
  // Each method's estimate against the peak of its first update in a fresh process, on a
  // room of 9.2k vertices (Documentation/Methods.md, "Memory"): within 1.3 either way.
  // Measured on the 2-core VM (TBB, Embree): links 1.11, instant radiosity 1.05, implicit
  // visibility 0.94 (1.34 on the 16-core GPU machine before it sampled its links), photon
  // mapping 1.10.
  expectEveryMethodEstimatesItsMeasuredPeak({});
}

TEST(TestMemoryBudget, EveryMethodEstimatesAModelInNoRoomsMeasuredPeak)
{
  // The torso stands in no room: most rays and light paths leave it. The link method's rows
  // keep a fraction of the links three per ray would make, and implicit visibility's leaves
  // see few nodes (from the sizes alone they were estimated at 4.9 and 4.3 times their
  // peaks; from a sample 1.00 and 1.04-1.09); the light paths take a second pass of more
  // paths, which the estimate takes in once it is known (photon mapping was at 0.17 without
  // it, now 0.95; instant radiosity 0.97-1.13).
  expectEveryMethodEstimatesItsMeasuredPeak("torso");
}

TEST(TestMemoryBudget, ABudgetBetweenTheSampledEstimateAndTheBoundLetsTheUpdateRun)
{
  // The torso again: its sampled estimate is under half the bound, and a budget between the
  // two lets the update run where the sizes alone refused it.
  const Scene s = makeStandardScene("torso");
  SolverOptions o;
  o.backend = Backend::Cpu;
  const std::uint64_t sampled = firstUpdateEstimate(s, o), sizes = sizeEstimate(s, o);
  ASSERT_LT(2 * sampled, sizes);
  o.memoryBudget = (sampled + sizes) / 2;
  Solver solver;
  EXPECT_NO_THROW(solver.update(s, o));
  EXPECT_EQ(solver.stats().hostBytesEstimated, sampled);
  EXPECT_GT(solver.stats().memorySampledPerElement, 0.0);
  EXPECT_TRUE(solver.stats().ran("Links"));
}

TEST(TestMemoryBudget, ARefusalBeforeTheSampleSaysWhatFitsTheWholeUpdate)
{
  // Under a budget that the link method's first stage (its ray structures) alone exceeds,
  // the update is refused before its rows are sampled, and the mesh it advises must fit the
  // whole update (from the sizes alone, nothing sampled), not only that stage.
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  o.backend = Backend::Cpu;
  const engine::MethodSpec& spec = engine::methodSpec(o.method);
  const MemoryShape shape = MemoryShape::of(s);
  o.memoryBudget = spec.estimateMemory(shape, o, 1u, false).hostBytes * 9 / 10; // stage 0: Geometry
  const engine::MemoryVerdict whole = engine::judgeMemory(spec, shape, o, kAllStages, false, o.memoryBudget);
  ASSERT_GT(whole.verticesThatFit, 0u);
  const std::uint64_t fit = verticesThatFitOnRefusal(s, o);
  EXPECT_EQ(fit, whole.verticesThatFit);
  MemoryShape advised = shape;
  advised.vertices = fit;
  advised.triangles = shape.triangles * advised.vertices / shape.vertices;
  EXPECT_LE(spec.estimateMemory(advised, o, kAllStages, false).hostBytes, o.memoryBudget);
}

TEST(TestMemoryBudget, EveryMethodIsRefusedOverTheBudget)
{
  // Every method declares its memory, so a budget below its estimate refuses it with the
  // size of mesh that would fit (what the filter's automatic proxy is made of).
  const Scene s = test::roomWithBlock();
  for (const Method method : { Method::Links, Method::InstantRadiosity, Method::ImplicitVisibility,
         Method::PhotonMapping })
  {
    SolverOptions o;
    o.backend = Backend::Cpu;
    o.method = method;
    const std::uint64_t full = firstUpdateEstimate(s, o);
    ASSERT_GT(full, 0u) << engine::methodSpec(method).name();
    o.memoryBudget = full * 9 / 10;
    Solver solver;
    try
    {
      solver.update(s, o);
      ADD_FAILURE() << engine::methodSpec(method).name() << " was not refused";
    }
    catch (const OutOfMemoryBudget& e)
    {
      EXPECT_NE(std::string(e.what()).find(engine::methodSpec(method).name()), std::string::npos) << e.what();
      EXPECT_LT(e.verticesThatFit(), s.vertexCount());
    }
  }
}

TEST(TestMemoryBudget, ASecondPassOfLightPathsOverTheBudgetIsRefused)
{
  // The torso stands in no room: most photons leave it, and a second pass of up to 64 times
  // the paths looks for the rest. The estimate counts the first pass only, so the second is
  // checked against what the budget leaves before its paths are allocated.
  const Scene s = makeStandardScene("torso");
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.method = Method::PhotonMapping;
  o.photonMapping.photons = 16384;
  o.photonMapping.clusters = 256;
  o.photonMapping.gatherRays = 16;
  o.memoryBudget = sizeEstimate(s, o) + (std::uint64_t(64) << 10);
  Solver solver;
  try
  {
    solver.update(s, o);
    FAIL() << "not refused";
  }
  catch (const OutOfMemoryBudget& e)
  {
    EXPECT_NE(std::string(e.what()).find("light paths mostly leave this scene"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("NumberOfPhotons"), std::string::npos) << e.what();
    EXPECT_EQ(e.verticesThatFit(), 0u); // a proxy would not help
  }
  // Under a budget that leaves room for it, the same update runs.
  o.memoryBudget = 0;
  EXPECT_NO_THROW(solver.update(s, o));
}
