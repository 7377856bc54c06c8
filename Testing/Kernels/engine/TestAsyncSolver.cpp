#include "SceneFixtures.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Scenes.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>
#include <chrono>
#include <thread>

using namespace linkgi;

namespace
{
SolverOptions options()
{
  SolverOptions o;
  o.raysPerVertex = 64;
  return o;
}

/// The room with its light scaled by k: direct irradiance is exactly linear in k.
Scene roomWithLight(float k)
{
  Scene s = test::roomWithBlock();
  s.lights[0].intensity = s.lights[0].intensity * k;
  return s;
}
}

TEST(TestAsyncSolver, ResultsBelongToOneRequest)
{
  // Requests with light scale k = 1..20 fired back to back, faster than any machine solves
  // (a fixed spacing is not: a GPU's light-only update beats a quarter of a full CPU solve):
  // every published result must be exactly one request's solution (direct = k * direct(1)
  // everywhere for the k of its id), never a mix, and the last request must be the one
  // that ends up shown.
  const Solution unit = Solver().update(roomWithLight(1.f), options());
  std::atomic<int> published{ 0 }; // before the solver: outlives its worker's callbacks
  AsyncSolver async(1);
  async.setOnPublish([&](std::uint64_t) { ++published; });
  std::uint64_t last = 0;
  for (int k = 1; k <= 20; ++k)
  {
    last = async.request(roomWithLight(float(k)), options());
    if (const auto r = async.latest())
    {
      const float scale = float(r->request); // request ids are 1..20, as k
      for (std::size_t i = 0; i < unit.elementCount(); i += 7)
      {
        ASSERT_NEAR(r->solution.direct[i].x, scale * unit.direct[i].x, 1e-4f * scale * (1.f + unit.direct[i].x));
      }
    }
  }
  ASSERT_TRUE(async.wait(last, 60.0));
  const auto final = async.latest();
  EXPECT_EQ(final->request, last);
  EXPECT_LT(published.load(), 20); // replaced requests were dropped, not queued
  const Solution fresh = Solver().update(roomWithLight(20.f), options());
  for (std::size_t i = 0; i < fresh.elementCount(); ++i)
  {
    ASSERT_EQ(final->solution.radiance[i], fresh.radiance[i]);
  }
}

TEST(TestAsyncSolver, AbortRunningPolicy)
{
  // A slow update followed by a quick one once the slow one runs: by default the slow one is
  // finished and published first; with setAbortRunning(true) it is abandoned for the newer.
  for (const bool abort : { false, true })
  {
    // Declared before the solver, so they outlive its worker's callbacks.
    std::mutex m;
    std::vector<std::uint64_t> shown;
    AsyncSolver async(1);
    async.setAbortRunning(abort);
    async.setOnPublish([&](std::uint64_t id) {
      std::lock_guard<std::mutex> lock(m);
      shown.push_back(id);
    });
    SolverOptions slow = options();
    slow.raysPerVertex = 1024;
    const std::uint64_t first = async.request(test::roomWithBlock(0.1f), slow);
    // Generous limits: under a sanitizer on a loaded machine the slow update takes minutes.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
    while (async.solving() != first && std::chrono::steady_clock::now() < deadline)
    {
      std::this_thread::yield();
    }
    ASSERT_EQ(async.solving(), first);
    const std::uint64_t second = async.request(test::roomWithBlock(0.25f), options());
    ASSERT_TRUE(async.wait(second, 600.0));
    // The publish callback runs on the worker just after the result is visible to wait().
    const auto published = [&] {
      std::lock_guard<std::mutex> lock(m);
      return !shown.empty() && shown.back() == second;
    };
    // A deadline of its own: the slow update may have used up the first one.
    const auto callbackDeadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
    while (!published() && std::chrono::steady_clock::now() < callbackDeadline)
    {
      std::this_thread::yield();
    }
    std::lock_guard<std::mutex> lock(m);
    if (abort)
    {
      EXPECT_EQ(shown, std::vector<std::uint64_t>({ second }));
    }
    else
    {
      EXPECT_EQ(shown, std::vector<std::uint64_t>({ first, second }));
    }
  }
}

TEST(TestAsyncSolver, RepeatedRequestsAreNotNewWork)
{
  AsyncSolver async(1);
  const Scene s = test::roomWithBlock();
  const std::uint64_t id = async.request(s, options());
  EXPECT_EQ(async.request(s, options()), id); // pending or running
  ASSERT_TRUE(async.wait(id, 60.0));
  EXPECT_EQ(async.request(s, options()), id); // published
  // Any option counts, also those no stage reads (where it runs).
  SolverOptions elsewhere = options();
  elsewhere.backend = elsewhere.backend == Backend::Cpu ? Backend::Auto : Backend::Cpu;
  EXPECT_GT(async.request(s, elsewhere), id);
  ASSERT_TRUE(async.wait(id + 1, 60.0));
  Scene moved = s;
  moved.lights[0].position.x += 0.1f;
  EXPECT_GT(async.request(moved, options()), id);
}

// Once the newest request's result is published the solver is idle: a render loop that
// shows that result never also reports work pending (the filter's LinkGI.Pending). The
// worker used to leave its update a moment after publishing; a callback that sleeps on
// publish holds that moment open. A failed request leaves it idle with its error too.
TEST(TestAsyncSolver, APublishedResultLeavesTheSolverIdle)
{
  AsyncSolver async(1);
  async.setOnPublish([](std::uint64_t) { std::this_thread::sleep_for(std::chrono::milliseconds(50)); });
  Scene s = test::roomWithBlock();
  for (int k = 1; k <= 3; ++k)
  {
    s.lights[0].position.x += 0.05f;
    const std::uint64_t id = async.request(s, options());
    ASSERT_TRUE(async.wait(id, 60.0));
    EXPECT_FALSE(async.busy()) << "request " << k << " is shown, nothing else was asked";
  }
  Scene broken = s;
  broken.positions[0].x = std::nanf("");
  const std::uint64_t failed = async.request(broken, options());
  EXPECT_FALSE(async.wait(failed, 60.0));
  EXPECT_FALSE(async.lastError().empty());
  EXPECT_FALSE(async.busy());
}

TEST(TestAsyncSolver, CancelKeepsTheLastResult)
{
  AsyncSolver async(1);
  const std::uint64_t first = async.request(test::roomWithBlock(0.25f), options());
  ASSERT_TRUE(async.wait(first, 60.0));
  const auto before = async.latest();
  // A much finer mesh on the CPU: ~40M link rays, seconds on any CPU; cancel it once the
  // worker has started it (waiting for that, not for a fixed time, which a fast machine
  // beats).
  SolverOptions slow = options();
  slow.raysPerVertex = 1024;
  slow.backend = Backend::Cpu;
  const std::uint64_t running = async.request(test::roomWithBlock(0.04f), slow);
  const auto started = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (async.solving() != running && std::chrono::steady_clock::now() < started)
  {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ASSERT_EQ(async.solving(), running);
  async.cancel();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (async.busy() && std::chrono::steady_clock::now() < deadline)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_FALSE(async.busy());
  EXPECT_EQ(async.latest(), before); // the same immutable result object
  EXPECT_EQ(async.latest()->request, first);
  // And the worker still serves new requests.
  const std::uint64_t next = async.request(test::roomWithBlock(0.25f), options());
  EXPECT_TRUE(async.wait(next, 60.0));
}

TEST(TestAsyncSolver, ErrorsAreReportedAndKeepTheLastResult)
{
  AsyncSolver async(1);
  const std::uint64_t good = async.request(test::roomWithBlock(), options());
  ASSERT_TRUE(async.wait(good, 60.0));
  Scene bad = test::roomWithBlock();
  bad.triangles.clear();
  const std::uint64_t failed = async.request(bad, options());
  EXPECT_FALSE(async.wait(failed, 60.0));
  EXPECT_NE(async.lastError().find("no triangles"), std::string::npos);
  EXPECT_EQ(async.latest()->request, good);
}

TEST(TestAsyncSolver, BlendingDampsIndirectOnly)
{
  AsyncSolver async(1);
  async.setBlend(0.25f);
  const Scene s = roomWithLight(1.f), t = roomWithLight(2.f);
  ASSERT_TRUE(async.wait(async.request(s, options()), 60.0));
  const Solution first = async.latest()->solution;
  ASSERT_TRUE(async.wait(async.request(t, options()), 60.0));
  const Solution& second = async.latest()->solution;
  // Direct light follows at once (x2); indirect moves a quarter of the way (x1.25).
  for (std::size_t i = 0; i < first.elementCount(); i += 5)
  {
    EXPECT_NEAR(second.direct[i].x, 2.f * first.direct[i].x, 1e-4f * (1.f + first.direct[i].x));
    EXPECT_NEAR(second.indirect[i].x, 1.25f * first.indirect[i].x, 1e-4f * (1.f + first.indirect[i].x));
  }
}

TEST(TestAsyncSolver, DeformingTorsoRefitsAndMatchesAFreshSolve)
{
  // The paper's deforming TORSO: a position-only change takes the refit path and gives the
  // same result as solving the deformed mesh from scratch.
  Solver solver;
  solver.update(makeStandardScene("torso", { 0.f }), options());
  SceneParams bent;
  bent.deformation = 0.6f;
  const Scene deformed = makeStandardScene("torso", bent);
  const Solution& refit = solver.update(deformed, options());
  EXPECT_TRUE(solver.stats().refitBvh);
  EXPECT_FALSE(solver.stats().builtBvh);
  const Solution fresh = Solver().update(deformed, options());
  for (std::size_t i = 0; i < fresh.elementCount(); ++i)
  {
    ASSERT_EQ(refit.radiance[i], fresh.radiance[i]) << i;
  }
}

TEST(TestAsyncSolver, DirectionSetDoesNotCrawlUnderDeformation)
{
  // The twist angle belongs to the vertex and its frame to the vertex normal, so a small
  // deformation moves each vertex's rays with it: frame-to-frame, the 256-ray solution must
  // change like a 1024-ray one (its noise pattern stays put) instead of re-rolling its noise.
  SceneParams p0, p1;
  p0.deformation = 0.30f;
  p1.deformation = 0.31f;
  const Scene a = makeStandardScene("torso", p0), b = makeStandardScene("torso", p1);
  const auto indirect = [](const Scene& s, std::uint32_t rays, std::uint32_t seed) {
    SolverOptions o;
    o.raysPerVertex = rays;
    o.seed = seed;
    return Solver().update(s, o).indirect;
  };
  const std::vector<Vec3f> ta = indirect(a, 1024, 0), tb = indirect(b, 1024, 0);
  const std::vector<Vec3f> xa = indirect(a, 256, 0);
  // Relative RMS of (256-ray change - 1024-ray change) from frame a to frame b.
  const auto crawl = [&](const std::vector<Vec3f>& xb) {
    double change = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < xa.size(); ++i)
    {
      const double d = luminance(xb[i] - xa[i]) - luminance(tb[i] - ta[i]);
      change += d * d;
      scale += luminance(ta[i]) * luminance(ta[i]);
    }
    return std::sqrt(change / scale);
  };
  const double kept = crawl(indirect(b, 256, 0));
  const double rerolled = crawl(indirect(b, 256, 1)); // the twist re-rolled between the frames
  std::printf("crawl: %.4f with the vertex's own twist, %.4f re-rolled\n", kept, rerolled);
  // Measured 0.82% and 2.16%; a twist that followed the frame instead of the vertex would
  // change as much as a re-rolled one.
  EXPECT_LT(kept, 0.5 * rerolled);
}

#ifdef __linux__
namespace
{
/// Every core kept busy at normal priority while it lives: another program that wants the
/// whole machine.
class BusyCores
{
public:
  BusyCores()
  {
    for (unsigned i = 0; i < std::max(1u, std::thread::hardware_concurrency()); ++i)
    {
      spinners.emplace_back([this] {
        while (!done.load(std::memory_order_relaxed))
        {
        }
      });
    }
  }
  ~BusyCores()
  {
    done = true;
    for (std::thread& t : spinners)
    {
      t.join();
    }
  }

private:
  std::atomic<bool> done{ false };
  std::vector<std::thread> spinners;
};
}

constexpr std::chrono::milliseconds kPause{ 1100 }; // longer than a continuous change's gaps

TEST(TestAsyncSolver, ContinuousChangeYieldsButNeverStarves)
{
  // Requests less than a second apart are solved in the idle scheduling class. With every
  // core busy at normal priority, such an update gets a few thousandths of a core (this one,
  // ~0.1 s of work alone, took 30 s that way). Once the requests stop, the worker must give
  // up on it within a second or two (yielding() turns false) and run it again at nice 10,
  // where it finishes while the cores stay busy (in 4 s here, slower under sanitizers).
  // The policy is about CPU time: on the CPU backend, so that a machine with a GPU (where a
  // light move is a few milliseconds of host work, over before a 10 ms poll sees it yield)
  // tests what a machine without one does.
  using Clock = std::chrono::steady_clock;
  const Scene room = test::roomWithBlock(0.03f);
  const auto options = [] {
    SolverOptions o = ::options();
    o.backend = Backend::Cpu;
    return o;
  };
  const auto lit = [&room](float k) { // the light moved by k steps
    Scene s = room;
    s.lights[0].position.x += 0.05f * k;
    return s;
  };
  AsyncSolver async(1);
  ASSERT_TRUE(async.wait(async.request(lit(1.f), options()), 300.0)); // the links
  // Two requests back to back: the first after a pause (nice 10), the second right after
  // it (the idle class, unless turned off). Returns how long the update was seen yielding
  // (0: never).
  const auto change = [&](float k) {
    std::this_thread::sleep_for(kPause);
    async.request(lit(k), options());
    const std::uint64_t last = async.request(lit(k + 1.f), options());
    std::optional<Clock::time_point> from, to;
    const Clock::time_point start = Clock::now();
    while (!async.wait(last, 0.01) && Clock::now() - start < std::chrono::seconds(300))
    {
      const bool yielding = async.yielding();
      if (yielding && !from)
      {
        from = Clock::now();
      }
      if (!yielding && from && !to)
      {
        to = Clock::now();
      }
    }
    EXPECT_TRUE(async.wait(last, 0.0)) << "request " << last << " never finished";
    return from ? std::chrono::duration<double>(to.value_or(Clock::now()) - *from).count() : 0.0;
  };
  async.setYieldToInteraction(false);
  EXPECT_EQ(change(2.f), 0.0) << "turned off, the continuous change still yielded";
  async.setYieldToInteraction(true);

  BusyCores busy;
  const double yielded = change(4.f);
  EXPECT_GT(yielded, 0.0) << "the continuous change never ran in the idle class";
  // kContinuous (1 s) after the last request plus up to two 0.5 s windows, and slack.
  EXPECT_LT(yielded, 4.0) << "the starving idle-class update was not given up on";
  // Stopped and run again, it is still exactly that request's solution.
  const Solution fresh = Solver().update(lit(5.f), options());
  const Solution& shown = async.latest()->solution;
  for (std::size_t i = 0; i < fresh.elementCount(); ++i)
  {
    ASSERT_EQ(shown.radiance[i], fresh.radiance[i]);
  }
}
#endif
