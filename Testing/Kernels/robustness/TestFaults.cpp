// Faults during an update: an abort asked for by another thread while the solver runs, on
// the Solver and on the AsyncSolver. The previous result stays whole and the next update is
// exactly a fresh solver's. (Out of GPU memory in the middle of an update: TestFaultsCuda.)
#include "SceneFixtures.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <string>
#include <thread>

using namespace linkgi;

namespace
{
SolverOptions options()
{
  SolverOptions o;
  o.raysPerVertex = 64;
  o.backend = Backend::Cpu;
  return o;
}

Scene moved(Scene s, float dy)
{
  for (Vec3f& p : s.positions)
  {
    p.y += dy * p.x;
  }
  return s;
}

void expectSameBits(const Solution& a, const Solution& b)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  EXPECT_EQ(std::memcmp(a.direct.data(), b.direct.data(), sizeof(Vec3f) * a.elementCount()), 0);
  EXPECT_EQ(std::memcmp(a.indirect.data(), b.indirect.data(), sizeof(Vec3f) * a.elementCount()), 0);
  EXPECT_EQ(std::memcmp(a.radiance.data(), b.radiance.data(), sizeof(Vec3f) * a.elementCount()), 0);
}
}

TEST(TestFaults, AnAbortFromAnotherThreadKeepsThePreviousResult)
{
  // The update of a deformed room waits at the start of each stage in turn (the stages
  // before it done and staged) until a second thread asks it to abort: the solver then
  // throws Aborted, still shows the room it solved before, and its next update of the
  // deformed room is a fresh solver's.
  const Scene room = test::roomWithBlock();
  const Scene deformed = moved(room, 0.1f);
  for (const char* stage : { "Geometry", "Links", "LightLinks", "Bounces" })
  {
    SCOPED_TRACE(stage);
    Solver solver;
    solver.update(room, options());
    const Solution before = solver.solution();

    std::atomic<bool> halfway{ false }, abort{ false };
    const ProgressCallback progress = [&](const char* now, double fraction) {
      if (std::string(now) == stage && !halfway)
      {
        halfway = true;
        while (!abort) // the other thread decides
        {
          std::this_thread::yield();
        }
      }
      return !abort;
    };
    bool aborted = false;
    std::thread worker([&] {
      try
      {
        solver.update(deformed, options(), progress);
      }
      catch (const Aborted&)
      {
        aborted = true;
      }
    });
    std::thread requester([&] {
      while (!halfway)
      {
        std::this_thread::yield();
      }
      abort = true;
    });
    requester.join();
    worker.join();
    ASSERT_TRUE(aborted);
    expectSameBits(solver.solution(), before);

    solver.update(deformed, options());
    Solver fresh;
    fresh.update(deformed, options());
    expectSameBits(solver.solution(), fresh.solution());
  }
}

TEST(TestFaults, ACancelFromAnotherThreadPublishesNoMix)
{
  // AsyncSolver::cancel() from a thread of its own while the worker solves a deformed room:
  // what is shown afterwards is exactly one request's solution (the room, or the deformed
  // room if it finished first), and the next request is solved exactly.
  const Scene room = test::roomWithBlock();
  const Scene deformed = moved(room, 0.1f);
  Solution roomSolution, deformedSolution;
  {
    Solver s;
    roomSolution = s.update(room, options());
    deformedSolution = s.update(deformed, options());
  }
  AsyncSolver async(1);
  const std::uint64_t first = async.request(room, options());
  ASSERT_TRUE(async.wait(first, 60.0));
  const std::uint64_t second = async.request(deformed, options());
  std::thread canceller([&] {
    while (async.solving() != second && async.busy())
    {
      std::this_thread::yield();
    }
    async.cancel();
  });
  canceller.join();
  async.wait(second, 60.0);
  const auto shown = async.latest();
  ASSERT_TRUE(shown);
  ASSERT_TRUE(shown->request == first || shown->request == second);
  expectSameBits(shown->solution, shown->request == first ? roomSolution : deformedSolution);
  EXPECT_FALSE(async.busy());

  const Scene again = moved(room, -0.1f);
  const std::uint64_t third = async.request(again, options());
  ASSERT_TRUE(async.wait(third, 60.0));
  Solver fresh;
  fresh.update(again, options());
  expectSameBits(async.latest()->solution, fresh.solution());
}
