#include "BenchProgressive.h"
#include "BenchStats.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Error.h"
#include "shared/Metrics.h"
#include "cpu/Parallel.h"
#include "engine/Pipeline.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <sstream>
#include <vector>

namespace linkgi::bench
{
namespace
{
using Clock = std::chrono::steady_clock;

/// The sampling the stage's method used, in its own words.
std::string samplingOf(const SolverOptions& o)
{
  return engine::methodSpec(o.method).sampling(o);
}

struct Published
{
  std::shared_ptr<const AsyncResult> result;
  double ms; // after the request
};

/// Drives one AsyncSolver through the update kinds; `progressive` on or off.
class Driver
{
public:
  explicit Driver(bool progressive) : async(workerCount())
  {
    async.setProgressive(progressive);
    async.setOnPublish([this](std::uint64_t) {
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      std::lock_guard<std::mutex> lock(mutex);
      seen.push_back({ async.latest(), ms });
    });
  }
  /// Solves `scene` and returns what was published for it, the final stage last.
  std::vector<Published> solve(const Scene& scene, const SolverOptions& options)
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      seen.clear();
      start = Clock::now();
    }
    const std::uint64_t id = async.request(scene, options);
    if (!async.wait(id))
    {
      throw Error("The progressive update failed: " + async.lastError());
    }
    const auto final = async.latest();
    for (;;) // the publish callback runs after wait() returns
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!seen.empty() && seen.back().result == final)
      {
        return seen;
      }
    }
  }

private:
  std::mutex mutex;
  std::vector<Published> seen;
  Clock::time_point start;
  AsyncSolver async; // last: its worker's callbacks use the members above
};

std::vector<Vec3f> total(const Solution& s)
{
  std::vector<Vec3f> t(s.elementCount());
  for (std::size_t i = 0; i < t.size(); ++i)
  {
    t[i] = s.direct[i] + s.indirect[i];
  }
  return t;
}

/// One update's stages as JSON, with the error of each against the final one.
std::string stagesJson(const std::vector<Published>& stages, const std::vector<float>& areas)
{
  const Solution& exact = stages.back().result->solution;
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < stages.size(); ++i)
  {
    const AsyncResult& r = *stages[i].result;
    const auto indirect = relativeRmse(r.solution.indirect, exact.indirect, areas);
    const auto combined = relativeRmse(total(r.solution), total(exact), areas);
    out << (i ? "," : "") << "{\"stage\":" << r.stage << ",\"of\":" << r.stages << ",\"ms\":" << stages[i].ms
        << ",\"solve_ms\":" << r.stats.msTotal << ",\"rel_rmse_indirect\":" << indirect.relRmseLuminance
        << ",\"rel_rmse_total\":" << combined.relRmseLuminance << ",\"backend\":\"" << r.stats.backend << "\"}";
  }
  out << "]";
  return out.str();
}
}

std::string progressiveJson(const std::string& name, const Scene& input, const SolverOptions& options, int repeat)
{
  std::vector<float> areas = vertexAreas(input);
  if (options.twoSided)
  {
    areas.insert(areas.end(), areas.begin(), areas.end());
  }
  std::ostringstream out;
  out << "{\"scene\":\"" << name << "\",\"vertices\":" << input.vertexCount() << ",\"threads\":" << workerCount()
      << ",\"final_sampling\":\"" << samplingOf(options) << "\"";
  // Each update kind: the progressive solver's stages, and the plain solver's time for the
  // same sequence of scenes.
  struct Kind
  {
    const char* name;
    std::vector<std::string> runs;
    std::vector<double> first, last, plain;
  };
  Kind kinds[3] = { { "apply", {}, {}, {}, {} }, { "deform", {}, {}, {}, {} }, { "light", {}, {}, {}, {} } };
  for (int r = 0; r < repeat; ++r)
  {
    // A fresh pair per run, in a process that has measured nothing: "apply" is the first
    // update of an application.
    AsyncSolver::forgetMeasurements();
    Driver progressive(true), plain(false);
    Scene scene = input;
    for (int k = 0; k < 3; ++k)
    {
      if (k == 1)
      {
        for (Vec3f& p : scene.positions)
        {
          p = p * Vec3f(1.f, 1.01f, 1.f); // stretched by 1%: every link moves
        }
      }
      if (k == 2)
      {
        if (scene.lights.empty())
        {
          continue;
        }
        scene.lights[0].position = scene.lights[0].position * 0.98f;
      }
      const std::vector<Published> stages = progressive.solve(scene, options);
      const std::vector<Published> alone = plain.solve(scene, options);
      kinds[k].runs.push_back(stagesJson(stages, areas));
      kinds[k].first.push_back(stages.front().ms);
      kinds[k].last.push_back(stages.back().ms);
      kinds[k].plain.push_back(alone.back().ms);
    }
  }
  for (const Kind& kind : kinds)
  {
    if (kind.runs.empty())
    {
      continue;
    }
    out << ",\"" << kind.name << "\":{\"median_first_ms\":" << median(kind.first)
        << ",\"median_final_ms\":" << median(kind.last) << ",\"median_plain_ms\":" << median(kind.plain)
        << ",\"runs\":[";
    for (std::size_t i = 0; i < kind.runs.size(); ++i)
    {
      out << (i ? "," : "") << kind.runs[i];
    }
    out << "]}";
  }
  out << "}";
  return out.str();
}
}
