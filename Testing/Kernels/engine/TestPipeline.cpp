// The orchestrator's decisions: what changed, which stages that makes stale, progress over
// the stages that run, and the per-stage records in the stats.
#include "SceneFixtures.h"

#include "engine/Pipeline.h"

#include "cuda/Cuda.h"
#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

using namespace linkgi;
using namespace linkgi::engine;

namespace
{
SolverOptions fast()
{
  SolverOptions o;
  o.raysPerVertex = 16;
  o.backend = Backend::Cpu;
  return o;
}

/// Names of the stale stages of the link-structure method for `changes`.
std::string staleLinkStages(Changes changes)
{
  const std::vector<StageSpec>& stages = methodSpec(Method::Links).stages();
  const std::uint32_t stale = staleStages(stages, changes);
  std::string names;
  for (std::size_t i = 0; i < stages.size(); ++i)
  {
    if (stale >> i & 1u)
    {
      names += std::string(names.empty() ? "" : " ") + stages[i].name;
    }
  }
  return names;
}
}

TEST(TestPipeline, ChangesNameWhatDiffers)
{
  const Scene a = test::roomWithBlock();
  const SolverOptions o = fast();
  EXPECT_EQ(changesBetween(a, o, a, o), 0u);

  Scene b = a;
  b.lights[0].position.y -= 0.1f;
  EXPECT_EQ(changesBetween(b, o, a, o), kLights);
  b = a;
  b.albedo[3].x *= 0.5f;
  EXPECT_EQ(changesBetween(b, o, a, o), kAlbedo);
  EXPECT_EQ(changesBetween(b, o, a, o, kAlbedo), 0u) << "known-same bits are not compared";
  b = a;
  b.positions[7].z += 0.01f;
  EXPECT_EQ(changesBetween(b, o, a, o), kPositions);
  b = a;
  b.triangles.pop_back();
  EXPECT_EQ(changesBetween(b, o, a, o), kTopology);
  b = a;
  b.environment.color = Vec3f(0.1f, 0.2f, 0.3f);
  EXPECT_EQ(changesBetween(b, o, a, o), kEnvironmentRadiance);

  SolverOptions p = o;
  p.seed = 9;
  EXPECT_EQ(changesBetween(a, p, a, o), kSampling);
  p = o;
  p.bounces = 5;
  EXPECT_EQ(changesBetween(a, p, a, o), kIteration);
  p = o;
  p.featureAngleDegrees = 10.f;
  EXPECT_EQ(changesBetween(a, p, a, o), kFiltering);
  p = o;
  p.backend = Backend::Auto;
  EXPECT_EQ(changesBetween(a, p, a, o), kPlacement);
}

TEST(TestPipeline, LinkStagesGoStaleByTheirDependencies)
{
  EXPECT_EQ(staleLinkStages(0), "");
  EXPECT_EQ(staleLinkStages(kLights), "LightLinks Bounces");
  EXPECT_EQ(staleLinkStages(kLightSampling), "LightLinks Bounces");
  EXPECT_EQ(staleLinkStages(kAlbedo | kEmission | kEnvironmentRadiance), "Bounces");
  EXPECT_EQ(staleLinkStages(kIteration | kFiltering), "Bounces");
  EXPECT_EQ(staleLinkStages(kSampling), "Links Bounces");
  EXPECT_EQ(staleLinkStages(kEnvironmentLayout), "Links Bounces");
  EXPECT_EQ(staleLinkStages(kSides), "Links LightLinks Bounces");
  // Geometry re-runs everything after it through the `after` bits.
  EXPECT_EQ(staleLinkStages(kNormals), "Geometry Links LightLinks Bounces");
  EXPECT_EQ(staleLinkStages(kEverything), "Geometry Links LightLinks Bounces");
  // Which backend runs is no stage's input; the backend's own sync decides.
  EXPECT_EQ(staleLinkStages(kPlacement), "Bounces");
}

TEST(TestPipeline, AfterBitsChainThroughAnyMethodsTable)
{
  // A made-up method: A <- B <- C, and D independent; stale sets follow the chain only.
  const std::vector<StageSpec> stages = {
    { "A", "", kPositions, 0u, 1.0 },
    { "B", "", kLights, 1u << 0, 1.0 },
    { "C", "", 0u, 1u << 1, 1.0 },
    { "D", "", kAlbedo, 0u, 1.0 },
  };
  EXPECT_EQ(staleStages(stages, kPositions), 0b0111u);
  EXPECT_EQ(staleStages(stages, kLights), 0b0110u);
  EXPECT_EQ(staleStages(stages, kAlbedo), 0b1000u);
  EXPECT_EQ(staleStages(stages, 0u), 0u);
}

TEST(TestPipeline, StatsRecordTheStagesThatRanAndTheirLifetimeRuns)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fast());
  const SolverStats& st = solver.stats();
  EXPECT_EQ(st.method, "links");
  EXPECT_EQ(st.backend, "cpu");
  for (const char* stage : { "Geometry", "Links", "LightLinks", "Bounces" })
  {
    EXPECT_TRUE(st.ran(stage)) << stage;
    EXPECT_GE(st.ms(stage), 0.0) << stage;
  }
  EXPECT_TRUE(st.ran("Compress")) << "the CPU backend reports its compression as a part";
  EXPECT_EQ(st.stage("Compress")->parent, "Links");
  double parts = 0.0;
  for (const StageStats& r : st.stages)
  {
    parts += r.ms;
  }
  EXPECT_LE(parts, st.msTotal + 1e-9) << "parts are not counted twice";

  s.lights[0].position.x += 0.05f;
  solver.update(s, fast());
  EXPECT_FALSE(solver.stats().ran("Geometry"));
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_FALSE(solver.stats().ran("Compress"));
  EXPECT_TRUE(solver.stats().ran("LightLinks"));
  EXPECT_EQ(solver.stats().runs("LinkBuilds"), 1u);
  EXPECT_EQ(solver.stats().runs("LightLinkBuilds"), 2u);
  EXPECT_EQ(solver.stats().runs("BounceRuns"), 2u);
}

TEST(TestPipeline, ProgressSpansTheStagesThatRun)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fast());
  s.lights[0].position.x += 0.05f;
  double first = -1.0, last = -1.0;
  std::vector<std::string> stages;
  solver.update(s, fast(), [&](const char* stage, double f) {
    EXPECT_GE(f, last);
    first = first < 0.0 ? f : first;
    last = f;
    if (stages.empty() || stages.back() != stage)
    {
      stages.push_back(stage);
    }
    return true;
  });
  // A light-only update still runs its bar from 0 to (nearly) 1, through its two stages.
  EXPECT_EQ(first, 0.0);
  EXPECT_GT(last, 0.5);
  EXPECT_LE(last, 1.0);
  EXPECT_EQ(stages.front(), "LightLinks");
}

TEST(TestPipeline, ResetRerunsEveryStageAndKeepsValidationWarnings)
{
  Scene s = test::roomWithBlock();
  s.triangles.push_back({ { 0, 0, 1 } }); // degenerate: validation removes it, with a warning
  Solver solver;
  const Solution first = solver.update(s, fast());
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  solver.reset();
  const Solution second = solver.update(s, fast());
  for (const char* stage : { "Geometry", "Links", "LightLinks", "Bounces" })
  {
    EXPECT_TRUE(solver.stats().ran(stage)) << stage;
  }
  // The input differs from the validated copy, so it is validated again and warns again.
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  EXPECT_NE(solver.stats().warnings[0].find("degenerate"), std::string::npos);
  ASSERT_EQ(first.elementCount(), second.elementCount());
  for (std::size_t e = 0; e < first.elementCount(); ++e)
  {
    EXPECT_EQ(first.radiance[e].x, second.radiance[e].x);
    EXPECT_EQ(first.indirect[e].y, second.indirect[e].y);
  }
}

TEST(TestPipeline, AnAbortKeepsTheCachesThatTheFailedUpdateDidNotTouch)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fast());
  const Solution before = solver.solution();
  s.lights[0].position.x += 0.05f;
  // Abort inside the light links: the links were never touched and stay cached.
  EXPECT_THROW(solver.update(s, fast(), [](const char* stage, double) { return std::string(stage) != "LightLinks"; }),
    Aborted);
  EXPECT_EQ(solver.solution().radiance[0].x, before.radiance[0].x);
  solver.update(s, fast());
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_TRUE(solver.stats().ran("LightLinks"));
  EXPECT_EQ(solver.stats().runs("LinkBuilds"), 1u);

  // Abort after a deformation rebuilt the BVH: the caches belong to no committed scene now,
  // so the next update (back to the committed geometry) redoes every stage.
  Scene moved = s;
  for (Vec3f& p : moved.positions)
  {
    p.y *= 1.01f;
  }
  EXPECT_THROW(solver.update(moved, fast(), [](const char* stage, double) { return std::string(stage) != "Links"; }),
    Aborted);
  s.lights[0].position.x += 0.05f;
  solver.update(s, fast());
  EXPECT_TRUE(solver.stats().ran("Geometry"));
  EXPECT_TRUE(solver.stats().ran("Links"));
  Solver fresh;
  fresh.update(s, fast());
  for (std::size_t e = 0; e < fresh.solution().elementCount(); e += 11)
  {
    EXPECT_EQ(solver.solution().radiance[e].x, fresh.solution().radiance[e].x);
  }
}

TEST(TestPipeline, AnAbortBeforeAnyStageKeepsABackendOutOfDateOutOfDate)
{
  // The CPU solves scene A, the GPU then solves scene B (the CPU's caches are now out of
  // date), an update on the CPU is aborted before its first stage: the CPU must still count
  // as out of date, or a light change would reuse its links of scene A.
  if (cuda::devices().empty())
  {
    GTEST_SKIP() << "needs a CUDA device: the only other backend";
  }
  Scene a = test::roomWithBlock(), b = test::roomWithBlock();
  for (Vec3f& p : b.positions)
  {
    p.y *= 0.8f;
  }
  SolverOptions gpu = fast();
  gpu.backend = Backend::Cuda;
  Solver solver;
  solver.update(a, fast());
  solver.update(b, gpu);
  ASSERT_EQ(solver.stats().backend, "cuda");
  EXPECT_THROW(solver.update(b, fast(), [](const char*, double) { return false; }), Aborted);
  b.lights[0].position.x += 0.05f;
  solver.update(b, fast());
  EXPECT_TRUE(solver.stats().ran("Links")) << "the CPU's links belong to scene A";
  Solver fresh;
  fresh.update(b, fast());
  for (std::size_t e = 0; e < fresh.solution().elementCount(); e += 7)
  {
    EXPECT_EQ(solver.solution().radiance[e].x, fresh.solution().radiance[e].x);
  }
}
