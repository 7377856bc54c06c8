// Partitioned solves (SolverOptions::partition, issue 16): processes that each link (or, for
// instant radiosity and photon mapping, gather) only their rows and complete every bounce through an exchange
// give, together, the one-process result bit for bit. Two threads stand in for two MPI ranks.
#include "SceneFixtures.h"

#include "linkgi/Memory.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <chrono>
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
  SumExchange exchange(2);
  TwoProcesses out;
  Solver solvers[2];
  const auto run = [&](int p) {
    auto part = std::make_shared<Partition>();
    part->rows.resize(s.vertexCount());
    for (std::size_t e = 0; e < s.vertexCount(); ++e)
    {
      part->rows[e] = std::uint8_t(owner(e) == p);
    }
    part->exchange = [&exchange](std::vector<Vec3f>& v) { exchange(v); };
    SolverOptions mine = o;
    mine.partition = part;
    out.result[p] = solvers[p].update(s, mine);
    out.stats[p] = solvers[p].stats();
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  out.exchanges = exchange.exchanges;
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
  SumExchange exchange(2);
  std::vector<std::shared_ptr<Partition>> parts(2);
  for (int p = 0; p < 2; ++p)
  {
    parts[p] = std::make_shared<Partition>();
    parts[p]->rows.resize(s.vertexCount());
    for (std::size_t e = 0; e < s.vertexCount(); ++e)
    {
      parts[p]->rows[e] = std::uint8_t((e / 7) % 2 == std::size_t(p));
    }
    parts[p]->exchange = [&exchange](std::vector<Vec3f>& v) { exchange(v); };
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
  EXPECT_EQ(exchange.exchanges, int(o.bounces) + 1) << "the sky's irradiance, then one per bounce";
  for (int p = 0; p < 2; ++p)
  {
    EXPECT_TRUE(sameBits(result[p].indirect, one.indirect)) << "process " << p;
    EXPECT_TRUE(sameBits(result[p].radiance, one.radiance)) << "process " << p;
    EXPECT_LT(stats[p].linksCompressed, whole.stats().linksCompressed * 3 / 4) << "each links its rows only";
  }
  EXPECT_EQ(stats[0].linksCompressed + stats[1].linksCompressed, whole.stats().linksCompressed);

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
    EXPECT_LT(two.stats[p].linksCompressed, whole.stats().linksCompressed * 3 / 4) << "each pushes to its rows only";
    EXPECT_LT(two.stats[p].linksRaw, whole.stats().linksRaw) << "each links into its leaves' ancestors only";
  }
  EXPECT_EQ(two.stats[0].linksCompressed + two.stats[1].linksCompressed, whole.stats().linksCompressed);
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
  part->exchange = [](std::vector<Vec3f>&) {};
  o.partition = part;
  Solver solver;
  EXPECT_NE(test::errorOf([&] { solver.update(s, o); }).find("one flag per element"), std::string::npos);
}

TEST(TestPartition, ProcessesAgreeOnTheMemoryBudget)
{
  // Process 0 has a budget too small for the update, process 1 the machine's: both must
  // refuse it. Had process 1 gone on alone, it would have waited in the first exchange.
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = test::quickOptions();
  o.backend = Backend::Cpu;
  SumExchange exchange(2);
  AllReduce<std::uint64_t> least(2, [](std::uint64_t a, std::uint64_t b) { return std::min(a, b); });
  std::string refused[2];
  const auto run = [&](int p) {
    auto part = std::make_shared<Partition>();
    part->rows.resize(s.vertexCount());
    for (std::size_t e = 0; e < s.vertexCount(); ++e)
    {
      part->rows[e] = std::uint8_t(e % 2 == std::size_t(p));
    }
    part->exchange = [&exchange](std::vector<Vec3f>& v) { exchange(v); };
    part->smallest = [&least](std::uint64_t x) {
      std::vector<std::uint64_t> v{ x };
      least(v);
      return v[0];
    };
    SolverOptions mine = o;
    mine.partition = part;
    mine.memoryBudget = p == 0 ? 64 * 1024 : 0;
    Solver solver;
    try
    {
      solver.update(s, mine);
    }
    catch (const OutOfMemoryBudget& e)
    {
      refused[p] = e.what();
    }
    catch (const std::exception& e)
    {
      refused[p] = std::string("wrong error: ") + e.what();
    }
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  EXPECT_EQ(exchange.exchanges, 0) << "nobody solved";
  EXPECT_NE(refused[0].find("Not enough memory"), std::string::npos) << refused[0];
  EXPECT_NE(refused[1].find("the smallest of the budgets of the processes"), std::string::npos) << refused[1];
}
