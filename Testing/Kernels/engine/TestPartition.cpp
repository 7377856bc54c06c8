// Partitioned solves (SolverOptions::partition): processes that each link (or, for
// instant radiosity and photon mapping, gather) only their rows and complete every bounce through an exchange
// give, together, the one-process result bit for bit. Two threads stand in for two MPI ranks.
#include "SceneFixtures.h"

#include "methods/iv/IvBackends.h"

#include "linkgi/Memory.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <condition_variable>
#include <functional>
#include <stdexcept>
#include <mutex>
#include <thread>

using namespace linkgi;

namespace
{
/// An allreduce over `parties` threads: each brings its values, waits for the others and
/// takes the reduction. A thread that waits more than ten seconds throws instead of hanging:
/// a process that never comes is a test failure.
template <typename T>
class AllReduce
{
public:
  AllReduce(int parties, std::function<T(const T&, const T&)> op) : parties(parties), op(std::move(op)) {}

  void operator()(std::vector<T>& v)
  {
    std::unique_lock<std::mutex> lock(mutex);
    const std::uint64_t round = generation;
    if (arrived == 0)
    {
      reduced = v;
    }
    else
    {
      for (std::size_t i = 0; i < v.size(); ++i)
      {
        reduced[i] = op(reduced[i], v[i]);
      }
    }
    if (++arrived == parties)
    {
      result = reduced;
      arrived = 0;
      ++generation;
      ++exchanges;
      done.notify_all();
    }
    else if (!done.wait_for(lock, std::chrono::seconds(10), [&] { return generation != round; }))
    {
      throw std::runtime_error("the other process never came to the exchange");
    }
    v = result;
  }
  int exchanges = 0; ///< completed rounds

private:
  const int parties;
  const std::function<T(const T&, const T&)> op;
  std::mutex mutex;
  std::condition_variable done;
  int arrived = 0;
  std::uint64_t generation = 0;
  std::vector<T> reduced, result;
};

/// The partition's exchange: a sum of per-element RGB vectors.
struct SumExchange : AllReduce<Vec3f>
{
  explicit SumExchange(int parties) : AllReduce<Vec3f>(parties, [](const Vec3f& a, const Vec3f& b) { return a + b; }) {}
};

/// Every collective of `parties` processes (threads): a Partition's sum, least and count.
struct Collectives
{
  explicit Collectives(int parties)
    : sum(parties)
    , least(parties, [](std::uint64_t a, std::uint64_t b) { return std::min(a, b); })
    , count(parties, [](std::uint64_t a, std::uint64_t b) { return a + b; })
  {
  }
  /// A partition over these collectives, process p owning the elements e with owner(e) == p.
  template <typename Owner>
  std::shared_ptr<Partition> partition(std::size_t elements, int p, Owner owner)
  {
    auto part = std::make_shared<Partition>();
    part->rows.resize(elements);
    for (std::size_t e = 0; e < elements; ++e)
    {
      part->rows[e] = std::uint8_t(owner(e) == p);
    }
    part->sum = [this](std::vector<Vec3f>& v) { sum(v); };
    const auto one = [](AllReduce<std::uint64_t>& reduce, std::uint64_t x) {
      std::vector<std::uint64_t> v{ x };
      reduce(v);
      return v[0];
    };
    part->least = [this, one](std::uint64_t x) { return one(least, x); };
    part->count = [this, one](std::uint64_t x) { return one(count, x); };
    return part;
  }
  SumExchange sum;
  AllReduce<std::uint64_t> least, count;
};

/// Two processes (threads) solving `s` once, process p owning the vertices v with
/// owner(v) == p, through one SumExchange.
struct TwoProcesses
{
  Solution result[2];
  SolverStats stats[2];
  int exchanges = 0;
};

template <typename Owner>
TwoProcesses solveAsTwo(const Scene& s, const SolverOptions& o, Owner owner)
{
  Collectives collectives(2);
  TwoProcesses out;
  Solver solvers[2];
  const auto run = [&](int p) {
    SolverOptions mine = o;
    mine.partition = collectives.partition(s.vertexCount(), p, owner);
    out.result[p] = solvers[p].update(s, mine);
    out.stats[p] = solvers[p].stats();
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  out.exchanges = collectives.sum.exchanges;
  return out;
}
}

TEST(TestPartition, TwoProcessesGiveTheOneProcessResultBitForBit)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  Solver whole;
  const Solution one = whole.update(s, o);

  // Rows split in interleaved runs of 7 (not a contiguous half: any mask works).
  Collectives collectives(2);
  std::vector<std::shared_ptr<Partition>> parts(2);
  for (int p = 0; p < 2; ++p)
  {
    parts[p] = collectives.partition(s.vertexCount(), p, [](std::size_t e) { return int((e / 7) % 2); });
  }
  Solution result[2];
  SolverStats stats[2];
  Solver solvers[2];
  const auto run = [&](int p, const Scene& scene) {
    SolverOptions mine = o;
    mine.partition = parts[p];
    result[p] = solvers[p].update(scene, mine);
    stats[p] = solvers[p].stats();
  };
  std::thread other(run, 1, std::cref(s));
  run(0, s);
  other.join();
  EXPECT_EQ(collectives.sum.exchanges, int(o.bounces) + 1) << "the sky's irradiance, then one per bounce";
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_TRUE(sameBits(result[p].indirect, one.indirect)) << "process " << p;
    EXPECT_TRUE(sameBits(result[p].radiance, one.radiance)) << "process " << p;
    EXPECT_LT(stats[p].counter("LinksCompressed"), whole.stats().counter("LinksCompressed") * 3 / 4) << "each links its rows only";
  }
  EXPECT_EQ(stats[0].counter("LinksCompressed") + stats[1].counter("LinksCompressed"), whole.stats().counter("LinksCompressed"));

  // A light move: no relinking, the same agreement.
  Scene lit = s;
  lit.lights[0].position.x += 0.3f;
  const Solution oneLit = whole.update(lit, o);
  std::thread again(run, 1, std::cref(lit));
  run(0, lit);
  again.join();
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_FALSE(stats[p].ran("Links")) << "process " << p;
    EXPECT_TRUE(sameBits(result[p].indirect, oneLit.indirect)) << "process " << p;
  }
}

// Instant radiosity splits its gather by rows too: each process gathers its own elements,
// one exchange per update completes E_ind (the smoothing then sees every neighbour).
TEST(TestPartition, InstantRadiosityGathersOnlyItsRows)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  o.method = Method::InstantRadiosity;
  o.instantRadiosity.vplCount = 256;
  Solver whole;
  const Solution one = whole.update(s, o);
  const TwoProcesses two = solveAsTwo(s, o, [](std::size_t v) { return int(v % 2); });
  const Solution* result = two.result;
  const SolverStats* stats = two.stats;
  EXPECT_EQ(two.exchanges, 1) << "one exchange of E_ind";
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_TRUE(sameBits(result[p].indirect, one.indirect)) << "process " << p;
    EXPECT_TRUE(sameBits(result[p].radiance, one.radiance)) << "process " << p;
    EXPECT_LT(stats[p].rays, whole.stats().rays * 3 / 4) << "each gathers its rows only";
  }
  EXPECT_EQ(stats[0].rays + stats[1].rays, whole.stats().rays);
}

// Implicit visibility creates only the node links into its own leaves' ancestors, pushes them
// to its own leaves and gathers those rows of every bounce: the sky's irradiance and each
// bounce's E_ind are completed by exchanges before the tree pulls the radiance up.
TEST(TestPartition, ImplicitVisibilityPushesAndGathersOnlyItsRows)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  o.method = Method::ImplicitVisibility;
  o.implicitVisibility.binsPerSide = 8;
  Solver whole;
  const Solution one = whole.update(s, o);
  const TwoProcesses two = solveAsTwo(s, o, [](std::size_t v) { return int((v / 5) % 2); });
  EXPECT_EQ(two.exchanges, int(o.bounces) + 1) << "the sky's irradiance, then one per bounce";
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_TRUE(sameBits(two.result[p].indirect, one.indirect)) << "process " << p;
    EXPECT_TRUE(sameBits(two.result[p].radiance, one.radiance)) << "process " << p;
    EXPECT_LT(two.stats[p].counter("LinksCompressed"), whole.stats().counter("LinksCompressed") * 3 / 4) << "each pushes to its rows only";
    EXPECT_LT(two.stats[p].counter("LinksRaw"), whole.stats().counter("LinksRaw")) << "each links into its leaves' ancestors only";
  }
  EXPECT_EQ(two.stats[0].counter("LinksCompressed") + two.stats[1].counter("LinksCompressed"), whole.stats().counter("LinksCompressed"));
}

// Under MPI each process samples the link stage's memory on its own rows (a quarter of the
// mesh on one, three quarters on the other) and judges what it will hold itself: each
// sample within the sample's error of what that process's links take, less than one
// process that links all rows takes.
TEST(TestPartition, EachProcessSamplesTheMemoryOfItsOwnRows)
{
  const Scene s = makeStandardScene("cornell");
  const double nv = double(s.vertexCount());
  for (Method method : { Method::Links, Method::ImplicitVisibility })
  {
    SolverOptions o;
    o.backend = Backend::Cpu;
    o.method = method;
    o.raysPerVertex = 64;
    o.implicitVisibility.binsPerSide = 8;
    Solver whole;
    whole.update(s, o);
    const TwoProcesses two = solveAsTwo(s, o, [nv](std::size_t v) { return int(double(v) >= nv / 4); });
    const char* name = method == Method::Links ? "links" : "implicit visibility";
    for (int p = 0; p < 2; ++p)
    {
      // What this process's link stage holds, per vertex of the whole mesh, in the sample's
      // units: links, or bytes of node links and leaf entries.
      const SolverStats& st = two.stats[p];
      const double leaves = double(st.counter("LinksCompressed") + st.counter("LinksEnvironment"));
      const double held = method == Method::Links ? leaves / nv :
        iv::linkStageBytesPerVertex({ double(st.counter("LinksCreated")) / nv, double(st.counter("LinksRaw")) / nv,
          leaves / nv });
      const double sampled = st.memorySampledPerElement;
      std::printf("%s, process %d: sampled %.1f per vertex, holds %.1f (one process: sampled %.1f)\n", name, p,
        sampled, held, whole.stats().memorySampledPerElement);
      EXPECT_NEAR(sampled / held, 1.0, 0.15) << name << ", process " << p;
      EXPECT_LT(sampled, 0.9 * whole.stats().memorySampledPerElement) << name << ", process " << p;
      EXPECT_LT(st.hostBytesEstimated, whole.stats().hostBytesEstimated) << name << ", process " << p;
    }
  }
}

// Photon mapping splits its final gather by the clusters' samples and its caustics by rows:
// exchanges complete them, and every process interpolates the whole surface.
TEST(TestPartition, PhotonMappingGathersOnlyItsClusters)
{
  for (const char* name : { "cornell", "caustics" })
  {
    const Scene s = makeStandardScene(name);
    SolverOptions o;
    o.backend = Backend::Cpu;
    o.method = Method::PhotonMapping;
    o.photonMapping.photons = 65536;
    o.photonMapping.clusters = 512;
    o.photonMapping.gatherRays = 64;
    Solver whole;
    const Solution one = whole.update(s, o);
    const TwoProcesses two = solveAsTwo(s, o, [](std::size_t v) { return int((v / 64) % 2); });
    const Solution* result = two.result;
    const SolverStats* stats = two.stats;
    const bool caustics = !one.caustics.empty();
    EXPECT_EQ(two.exchanges, caustics ? 3 : 2) << name << ": irradiance and distances, then caustics";
    for (int p = 0; p < 2; ++p)
    {
      EXPECT_TRUE(sameBits(result[p].indirect, one.indirect)) << name << ", process " << p;
      EXPECT_TRUE(sameBits(result[p].radiance, one.radiance)) << name << ", process " << p;
      EXPECT_TRUE(sameBits(result[p].caustics, one.caustics)) << name << ", process " << p;
      EXPECT_LT(stats[p].rays, whole.stats().rays * 3 / 4) << name << ": each gathers its clusters only";
    }
    EXPECT_EQ(stats[0].rays + stats[1].rays, whole.stats().rays) << name;
  }
}

TEST(TestPartition, AMaskOfTheWrongSizeIsNamed)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  auto part = std::make_shared<Partition>();
  part->rows.assign(3, 1);
  part->sum = [](std::vector<Vec3f>&) {};
  o.partition = part;
  Solver solver;
  EXPECT_NE(test::errorOf([&] { solver.update(s, o); }).find("one flag per element"), std::string::npos);
}

TEST(TestPartition, ProcessesAgreeOnTheMemoryBudget)
{
  // Process 0 has a budget too small for its part of the update, process 1 the machine's:
  // both must refuse it, and advise the same mesh. Had process 1 gone on alone, it would
  // have waited in the first exchange.
  const Scene s = makeStandardScene("cornell");
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  Solver alone;
  alone.update(s, o);
  Collectives collectives(2);
  std::string refused[2];
  std::uint64_t fit[2] = { 0, 0 };
  const auto run = [&](int p) {
    auto part = collectives.partition(s.vertexCount(), p, [](std::size_t e) { return int(e % 2); });
    SolverOptions mine = o;
    mine.partition = part;
    mine.memoryBudget = p == 0 ? alone.stats().hostBytesEstimated * 4 / 5 : 0;
    Solver solver;
    try
    {
      together(part.get(), [&] { solver.update(s, mine); }); // both fail: one agreement step each
    }
    catch (const OutOfMemoryBudget& e)
    {
      refused[p] = e.what();
      fit[p] = e.verticesThatFit();
    }
    catch (const std::exception& e)
    {
      refused[p] = std::string("wrong error: ") + e.what();
    }
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  EXPECT_EQ(collectives.sum.exchanges, 0) << "nobody solved";
  EXPECT_NE(refused[0].find("Not enough memory"), std::string::npos) << refused[0];
  EXPECT_NE(refused[1].find("Not enough memory on another process"), std::string::npos) << refused[1];
  EXPECT_GT(fit[0], 0u) << refused[0];
  EXPECT_LT(fit[0], s.vertexCount()) << refused[0];
  EXPECT_EQ(fit[1], fit[0]) << refused[1];
}

// A process that fails in the middle of a partitioned update (here an abort at a chosen
// progress report of process 1) takes the others with it at their next collective step:
// they leave with PeerFailed instead of waiting for it in an exchange (the test's exchanges
// throw after ten seconds), every process keeps its previous result, and the next update
// gives the one-process result bit for bit.
TEST(TestPartition, AProcessThatFailsLeavesWithTheOthers)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  Solver whole;
  whole.update(s, o);
  Scene lit = s;
  lit.lights[0].position.x += 0.3f;
  const Solution oneLit = whole.update(lit, o);

  // Where process 1 fails in a light move: at its first progress report (before any
  // exchange), at its 11th (in the second of three bounces, after two of the four exchanges), after its
  // update (1000: the other finished its own), or not at all (-1).
  for (const int failAt : { 1, 11, 1000, -1 })
  {
    SCOPED_TRACE("process 1 fails at its report " + std::to_string(failAt));
    Collectives collectives(2);
    Solver solvers[2];
    Solution before[2];
    std::string outcome[2];
    const auto run = [&](int p, const Scene& scene, int failAtReport) {
      SolverOptions mine = o;
      mine.partition = collectives.partition(s.vertexCount(), p, [](std::size_t e) { return int((e / 3) % 2); });
      before[p] = solvers[p].solution();
      int reports = 0;
      const ProgressCallback progress = [&](const char*, double) {
        return !(p == 1 && ++reports == failAtReport);
      };
      try
      {
        together(mine.partition.get(), [&] {
          solvers[p].update(scene, mine, progress);
          if (p == 1 && failAtReport == 1000)
          {
            throw Error("process 1 failed after its update");
          }
        });
        outcome[p] = "solved";
      }
      catch (const PeerFailed& e)
      {
        outcome[p] = "peer failed: " + std::string(e.what());
      }
      catch (const std::exception& e)
      {
        outcome[p] = e.what();
      }
    };
    // A solved scene first, so "kept" is something; then a light move that fails.
    std::thread first(run, 1, std::cref(s), -1);
    run(0, s, -1);
    first.join();
    ASSERT_EQ(outcome[0], "solved");
    ASSERT_EQ(outcome[1], "solved");
    const int exchangesBefore = collectives.sum.exchanges;
    std::thread other(run, 1, std::cref(lit), failAt);
    run(0, lit, failAt);
    other.join();
    const int exchanged = collectives.sum.exchanges - exchangesBefore;
    if (failAt == 11)
    {
      EXPECT_GT(exchanged, 0) << "failed between two exchanges";
      EXPECT_LT(exchanged, int(o.bounces) + 1) << "failed between two exchanges";
    }
    if (failAt < 0)
    {
      EXPECT_EQ(outcome[0], "solved");
      EXPECT_EQ(outcome[1], "solved");
    }
    else
    {
      EXPECT_NE(outcome[0].find("peer failed: This update failed on 1 of the other processes"), std::string::npos)
        << outcome[0];
      EXPECT_EQ(outcome[1], failAt == 1000 ? "process 1 failed after its update" :
                                             "The update was aborted; the previous result is kept.");
      for (int p = 0; p < 2 && failAt != 1000; ++p)
      {
        EXPECT_TRUE(sameBits(solvers[p].solution().indirect, before[p].indirect)) << "process " << p << " kept its result";
      }
    }
    // And the next update of the moved light completes on both, as one process's.
    std::thread last(run, 1, std::cref(lit), -1);
    run(0, lit, -1);
    last.join();
    for (int p = 0; p < 2; ++p)
    {
      EXPECT_EQ(outcome[p], "solved");
      EXPECT_TRUE(sameBits(solvers[p].solution().indirect, oneLit.indirect)) << "process " << p;
    }
  }
}
