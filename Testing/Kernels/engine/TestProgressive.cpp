// Progressive updates: the plan of coarse stages (engine/Progression.h) and the AsyncSolver
// that publishes them before the final solution.
#include "SceneFixtures.h"

#include "engine/Pipeline.h"
#include "engine/Progression.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

using namespace linkgi;
using namespace linkgi::engine;

namespace
{
const Method kMethods[] = { Method::Links, Method::InstantRadiosity, Method::ImplicitVisibility,
  Method::PhotonMapping };

SolverOptions cpuOptions(Method method)
{
  SolverOptions o;
  o.method = method;
  o.backend = Backend::Cpu; // bit-identical finals are asserted on the deterministic backend
  o.raysPerVertex = 256;
  o.instantRadiosity.vplCount = 1024;
  o.photonMapping.photons = 16384;
  o.photonMapping.clusters = 256;
  o.photonMapping.gatherRays = 256;
  return o;
}

/// The options with every sampling count of every method cleared: what coarser() may change.
SolverOptions withoutSampling(SolverOptions o)
{
  o.raysPerVertex = 0;
  o.instantRadiosity.vplCount = 0;
  o.instantRadiosity.compensationRays = 0;
  o.implicitVisibility.binsPerSide = 0;
  o.photonMapping.photons = 0;
  o.photonMapping.gatherRays = 0;
  return o;
}

bool sameSolution(const Solution& a, const Solution& b)
{
  return sameBits(a.direct, b.direct) && sameBits(a.indirect, b.indirect) && sameBits(a.radiance, b.radiance);
}

/// Results the publish callback saw. The callback runs after wait() returns: seenAll() waits
/// until it saw `result` too.
struct Published
{
  std::mutex mutex;
  std::vector<std::shared_ptr<const AsyncResult>> results;
  void add(std::shared_ptr<const AsyncResult> r)
  {
    std::lock_guard<std::mutex> lock(mutex);
    results.push_back(std::move(r));
  }
  std::vector<std::shared_ptr<const AsyncResult>> seenAll(const std::shared_ptr<const AsyncResult>& result)
  {
    for (int i = 0; i < 10000; ++i)
    {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (std::find(results.begin(), results.end(), result) != results.end())
        {
          return results;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ADD_FAILURE() << "the publish callback never saw the latest result";
    return {};
  }
};

double meanOf(const std::vector<Vec3f>& values)
{
  double sum = 0.0;
  for (const Vec3f& e : values)
  {
    sum += e.x + e.y + e.z;
  }
  return values.empty() ? 0.0 : sum / double(values.size());
}

double meanIndirect(const Solution& s)
{
  return meanOf(s.indirect);
}
}

TEST(TestProgressive, CoarserSamplingIsValidSmallerAndTouchesSamplingOnly)
{
  for (const Method m : kMethods)
  {
    const MethodSpec& spec = methodSpec(m);
    SolverOptions o = cpuOptions(m);
    o.raysPerVertex = 256;
    o.instantRadiosity.vplCount = 4096;
    o.instantRadiosity.interleave = 16;
    o.photonMapping.photons = 262144;
    o.photonMapping.gatherRays = 256;
    const double work = spec.sampleWork(10000, o);
    ASSERT_GT(work, 0.0) << spec.name();
    double previous = 0.0;
    for (const double fraction : { 1.0 / 256, 1.0 / 16, 1.0 / 4 })
    {
      const SolverOptions c = spec.coarser(o, fraction);
      SCOPED_TRACE(std::string(spec.name()) + " at " + std::to_string(fraction));
      EXPECT_NO_THROW(validateOptions(c));
      EXPECT_TRUE(withoutSampling(c) == withoutSampling(o));
      const double coarseWork = spec.sampleWork(10000, c);
      EXPECT_LT(coarseWork, work);
      EXPECT_GE(coarseWork, previous); // a larger fraction never samples less
      // Near the fraction asked for, except where the method's least sampling holds it up.
      EXPECT_LE(coarseWork, std::max(2.0 * fraction * work, spec.sampleWork(10000, spec.coarser(o, 0.0))));
      previous = coarseWork;
    }
  }
}

TEST(TestProgressive, PlanAimsAtTheBudgetAndStaysWithinTheFinalsShare)
{
  const MethodSpec& links = methodSpec(Method::Links);
  SolverOptions o;
  o.raysPerVertex = 1024;
  const std::size_t elements = 100000;
  const double work = links.sampleWork(elements, o);
  ProgressionPlan plan; // 0.5 s, nothing measured yet

  // The first update: nothing measured, one coarse stage at 1/32 of the work.
  std::vector<SolverOptions> previews = planPreviews(links, elements, o, -1.0, plan);
  ASSERT_EQ(previews.size(), 1u);
  EXPECT_EQ(previews[0].raysPerVertex, 25u); // the square below 1024 / 32
  EXPECT_TRUE(o.lightOversampling);
  EXPECT_FALSE(previews[0].lightOversampling) << "a coarse stage's shadows are not oversampled";

  // A final predicted under four budgets is published alone.
  EXPECT_TRUE(planPreviews(links, elements, o, 1.9, plan).empty());

  // Measured: 1e-7 s per ray. The first stage aims at 0.5 s = 5e6 rays = 50 per vertex: the
  // square below, 49; then four times more while all of them stay within 10% of the final.
  plan.previewRate = 1e-7;
  const double finalSeconds = plan.previewRate * work; // 10.24 s
  previews = planPreviews(links, elements, o, finalSeconds, plan);
  ASSERT_FALSE(previews.empty());
  EXPECT_EQ(previews[0].raysPerVertex, 49u);
  double spent = 0.0;
  for (std::size_t i = 0; i < previews.size(); ++i)
  {
    const double seconds = plan.previewRate * links.sampleWork(elements, previews[i]);
    if (i > 0)
    {
      EXPECT_GT(previews[i].raysPerVertex, previews[i - 1].raysPerVertex);
      spent += seconds;
    }
  }
  EXPECT_LE(spent + plan.previewRate * links.sampleWork(elements, previews[0]), 0.1 * finalSeconds + 0.5);

  // A machine so fast that the budget buys more than a quarter of the work: no coarse stage.
  plan.previewRate = 1e-10;
  EXPECT_TRUE(planPreviews(links, elements, o, -1.0, plan).empty());
  // At the method's least sampling already: nothing coarser to show.
  o.raysPerVertex = 9;
  plan.previewRate = 0.0;
  EXPECT_TRUE(planPreviews(links, elements, o, -1.0, plan).empty());
}

TEST(TestProgressive, HistoryPredictsTheStaleStagesScaledByTheirWork)
{
  const MethodSpec& links = methodSpec(Method::Links);
  SolverStats stats;
  for (const StageSpec& s : links.stages())
  {
    StageStats st;
    st.name = s.name;
    st.ran = true;
    st.ms = 100.0;
    stats.stages.push_back(st);
  }
  StageStats part; // a part of the links stage counts as the stage's time
  part.name = "Compress";
  part.parent = "Links";
  part.ran = true;
  part.ms = 50.0;
  stats.stages.push_back(part);
  StageHistory history;
  SolverOptions o;
  EXPECT_LT(history.predictSeconds(1u, 1000.0), 0.0); // never ran: unknown
  history.record(links, stats, historyWork(links, 1000, o));
  const std::uint32_t stale = staleStages(links.stages(), kLights);
  EXPECT_NEAR(history.predictSeconds(stale, historyWork(links, 1000, o)), 0.2, 1e-12); // light links + bounces
  // Twice the elements, four times the rays: eight times the work.
  o.raysPerVertex *= 4;
  EXPECT_NEAR(history.predictSeconds(staleStages(links.stages(), kEverything), historyWork(links, 2000, o)),
    8 * 0.45, 1e-12);
}

TEST(TestProgressive, AFinalRecordsTheStagesItLeftToItsCoarseStage)
{
  const auto stage = [](const char* name, double ms, const char* parent = "") {
    StageStats st;
    st.name = name;
    st.parent = parent;
    st.ran = true;
    st.ms = ms;
    return st;
  };
  SolverStats coarse; // a coarse stage of the link method: every stage ran
  coarse.stages = { stage("Geometry", 40.0), stage("Links", 5.0), stage("Compress", 1.0, "Links"),
    stage("LightLinks", 30.0), stage("Bounces", 2.0) };
  coarse.msTotal = 78.0;
  SolverStats final; // the final, on the same solver: only what the sampling touches
  final.stages = { stage("Geometry", 0.0), stage("Links", 500.0), stage("Compress", 90.0, "Links"),
    stage("LightLinks", 0.0), stage("Bounces", 20.0) };
  final.stages[0].ran = final.stages[3].ran = false;
  final.msTotal = 610.0;
  const SolverStats merged = withStagesOf(final, coarse);
  EXPECT_TRUE(merged.ran("Geometry"));
  EXPECT_EQ(merged.ms("Geometry"), 40.0);
  EXPECT_EQ(merged.ms("LightLinks"), 30.0);
  EXPECT_EQ(merged.ms("Links"), 500.0); // the final's own, not the coarse stage's
  EXPECT_EQ(merged.ms("Compress"), 90.0);
  EXPECT_EQ(merged.msTotal, 680.0);
  StageHistory history;
  history.record(methodSpec(Method::Links), merged, 1.0);
  EXPECT_NEAR(history.predictSeconds(staleStages(methodSpec(Method::Links).stages(), kEverything), 1.0),
    0.68, 1e-12);
}

TEST(TestProgressive, EveryMethodPublishesACoarseStageThenExactlyTheFinalSolution)
{
  for (const Method m : kMethods)
  {
    const SolverOptions o = cpuOptions(m);
    SCOPED_TRACE(methodSpec(m).name());
    Scene scene = test::roomWithBlock();
    Published seen; // before the solver: outlives its worker's callbacks
    AsyncSolver::forgetMeasurements(); // as the first update of a process
    AsyncSolver async(2);
    async.setProgressive(true);
    async.setFirstStageSeconds(0.01);
    async.setOnPublish([&](std::uint64_t) { seen.add(async.latest()); });
    Solver reference; // the non-progressive solves of the same sequence of scenes
    for (int step = 0; step < 2; ++step)
    {
      if (step == 1)
      {
        for (Vec3f& p : scene.positions)
        {
          p.y *= 1.05f; // a deformation: what a time step of an animation does
        }
      }
      const std::uint64_t id = async.request(scene, o);
      ASSERT_TRUE(async.wait(id, 120.0)) << async.lastError();
      const Solution& exact = reference.update(scene, o);
      std::vector<std::shared_ptr<const AsyncResult>> mine;
      for (const auto& r : seen.seenAll(async.latest()))
      {
        if (r->request == id)
        {
          mine.push_back(r);
        }
      }
      ASSERT_FALSE(mine.empty());
      const auto& last = mine.back();
      ASSERT_TRUE(last->final());
      EXPECT_TRUE(sameSolution(last->solution, exact)) << "the final stage is the non-progressive solution";
      for (std::size_t i = 0; i < mine.size(); ++i)
      {
        EXPECT_EQ(mine[i]->stage, i + 1);
        EXPECT_EQ(mine[i]->stages, mine.size());
      }
      if (step == 0)
      {
        // The final's time unknown: the first update shows a coarse stage first, a solution
        // of the same light - the same direct light but at the shadows' edges (not
        // oversampled), indirect light of the same level.
        ASSERT_GE(mine.size(), 2u);
        const Solution& coarse = mine[0]->solution;
        EXPECT_NEAR(meanOf(coarse.direct), meanOf(exact.direct), 0.02 * meanOf(exact.direct));
        EXPECT_NEAR(meanIndirect(coarse), meanIndirect(exact), 0.3 * meanIndirect(exact));
        EXPECT_FALSE(sameBits(coarse.indirect, exact.indirect));
        // The final reuses what the coarse stage computed that the sampling does not touch:
        // every method's first stage (the surface's structures) ran there, not again.
        const std::string first = methodSpec(m).stages().front().name;
        EXPECT_TRUE(mine[0]->stats.ran(first));
        EXPECT_FALSE(last->stats.ran(first)) << first << " ran again in the final stage";
        EXPECT_TRUE(last->stats.ran("LightLinks")) << "the final traces its oversampled shadows";
      }
    }
  }
}

TEST(TestProgressive, ANewRequestDropsTheStagesLeftOfTheOldOne)
{
  // Requests faster than any stage: every request ends in its own final solution or in none
  // (superseded), the newest one in its final, and no stage of an older request is published
  // after a stage of a newer one.
  const SolverOptions o = cpuOptions(Method::Links);
  Published seen;
  AsyncSolver::forgetMeasurements();
  AsyncSolver async(2);
  async.setProgressive(true);
  async.setFirstStageSeconds(0.01);
  async.setOnPublish([&](std::uint64_t) { seen.add(async.latest()); });
  Scene scene = test::roomWithBlock();
  std::uint64_t last = 0;
  for (int k = 0; k < 6; ++k)
  {
    for (Vec3f& p : scene.positions)
    {
      p.y *= 1.01f;
    }
    last = async.request(scene, o);
  }
  ASSERT_TRUE(async.wait(last, 120.0)) << async.lastError();
  const auto latest = async.latest();
  EXPECT_EQ(latest->request, last);
  EXPECT_TRUE(latest->final());
  EXPECT_TRUE(sameSolution(latest->solution, Solver().update(scene, o)));
  const auto order = seen.seenAll(latest);
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    const AsyncResult &a = *order[i - 1], &b = *order[i];
    EXPECT_TRUE(b.request > a.request || (b.request == a.request && b.stage == a.stage + 1));
    EXPECT_TRUE(b.request == a.request || a.final() || b.stage == 1) << "a newer request starts at its first stage";
  }
}

#ifdef __linux__
// The first coarse stage, short and what the user waits for, runs at the priority of the
// thread that made the solver (the render loop's), the final's long work at nice 10. The
// publish callbacks run on the update's thread, so they read its priority stage by stage.
TEST(TestProgressive, TheFirstStageRunsAtTheCallersPriorityTheFinalAtNice10)
{
  const int caller = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  if (caller >= 10)
  {
    GTEST_SKIP() << "this thread runs at nice " << caller << ": both priorities are nice 10";
  }
  std::mutex mutex;
  std::vector<std::pair<std::uint32_t, int>> seen; // (stage, nice) at each publication
  AsyncSolver::forgetMeasurements(); // a first update: it has a coarse stage
  AsyncSolver async(1);
  async.setProgressive(true);
  async.setFirstStageSeconds(0.01);
  async.setOnPublish([&](std::uint64_t) {
    const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
    std::lock_guard<std::mutex> lock(mutex);
    seen.emplace_back(async.latest()->stage, nice);
  });
  const std::uint64_t id = async.request(test::roomWithBlock(), cpuOptions(Method::Links));
  ASSERT_TRUE(async.wait(id, 120.0)) << async.lastError();
  const std::uint32_t stages = async.latest()->stages;
  const auto allSeen = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return !seen.empty() && seen.back().first == stages;
  };
  // The final's callback runs just after wait() sees it published.
  for (int i = 0; i < 1000 && !allSeen(); ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GE(seen.size(), 2u);
  EXPECT_EQ(seen.front().first, 1u);
  EXPECT_EQ(seen.front().second, caller) << "the first coarse stage at the caller's priority";
  EXPECT_EQ(seen.back().second, 10) << "the final stage at nice 10";
}
#endif

TEST(TestProgressive, OffPublishesFinalsOnly)
{
  const SolverOptions o = cpuOptions(Method::Links);
  Published seen;
  AsyncSolver async(2);
  async.setOnPublish([&](std::uint64_t) { seen.add(async.latest()); });
  const std::uint64_t id = async.request(test::roomWithBlock(), o);
  ASSERT_TRUE(async.wait(id, 120.0));
  const auto latest = async.latest();
  EXPECT_EQ(seen.seenAll(latest).size(), 1u);
  EXPECT_TRUE(latest->final());
  EXPECT_EQ(latest->stages, 1u);
}
