#include "engine/Progression.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

namespace linkgi::engine
{
namespace
{
std::mutex ratesMutex;
std::map<std::pair<RateOf, std::pair<Method, Backend>>, double> rates;
}

std::size_t elementCount(const Scene& scene, const SolverOptions& options)
{
  return scene.vertexCount() * (options.twoSided ? 2 : 1);
}

double measuredRate(RateOf kind, const SolverOptions& options)
{
  std::lock_guard<std::mutex> lock(ratesMutex);
  const auto it = rates.find({ kind, { options.method, options.backend } });
  return it == rates.end() ? 0.0 : it->second;
}

void recordRate(RateOf kind, const SolverOptions& options, double secondsPerWork)
{
  std::lock_guard<std::mutex> lock(ratesMutex);
  rates[{ kind, { options.method, options.backend } }] = secondsPerWork;
}

void forgetRates()
{
  std::lock_guard<std::mutex> lock(ratesMutex);
  rates.clear();
}
std::uint32_t scaledSquare(std::uint32_t square, double fraction, std::uint32_t least)
{
  const auto side = [](double n) { return static_cast<std::uint32_t>(std::floor(std::sqrt(n) + 1e-9)); };
  const std::uint32_t k = std::max(side(double(least)), side(fraction * double(square)));
  return std::min(square, k * k);
}

std::uint32_t scaledCount(std::uint32_t count, double fraction, std::uint32_t least)
{
  const double scaled = std::round(fraction * double(count));
  return std::min(count, std::max(least, static_cast<std::uint32_t>(std::max(0.0, scaled))));
}

SolverStats withStagesOf(const SolverStats& final, const SolverStats& coarse)
{
  SolverStats merged = final;
  for (const StageStats& stage : coarse.stages)
  {
    const StageStats* own = final.stage(stage.name);
    if (!stage.parent.empty() || !stage.ran || (own && own->ran))
    {
      continue;
    }
    for (const StageStats& part : coarse.stages)
    {
      if (&part != &stage && part.parent != stage.name)
      {
        continue;
      }
      const auto same = std::find_if(merged.stages.begin(), merged.stages.end(),
        [&](const StageStats& m) { return m.name == part.name; });
      if (same == merged.stages.end())
      {
        merged.stages.push_back(part);
      }
      else
      {
        *same = part;
      }
      merged.msTotal += part.ms;
    }
  }
  return merged;
}

double historyWork(const MethodSpec& spec, std::size_t elements, const SolverOptions& options)
{
  const double work = spec.sampleWork(elements, options);
  return work > 0.0 ? work : double(elements);
}

void StageHistory::record(const MethodSpec& spec, const SolverStats& stats, double amount)
{
  const auto& stages = spec.stages();
  ms.resize(stages.size(), 0.0);
  work.resize(stages.size(), 0.0);
  for (std::size_t i = 0; i < stages.size(); ++i)
  {
    const StageStats* stage = stats.stage(stages[i].name);
    if (!stage || !stage->ran)
    {
      continue;
    }
    double total = stage->ms;
    for (const StageStats& part : stats.stages)
    {
      total += part.parent == stages[i].name ? part.ms : 0.0;
    }
    ms[i] = total;
    work[i] = amount;
  }
}

double StageHistory::predictSeconds(std::uint32_t stale, double amount) const
{
  double seconds = 0.0;
  for (std::size_t i = 0; i < 32; ++i)
  {
    if (!(stale & (1u << i)))
    {
      continue;
    }
    if (i >= ms.size() || !(work[i] > 0.0))
    {
      return -1.0;
    }
    seconds += 1e-3 * ms[i] * amount / work[i];
  }
  return seconds;
}

std::vector<SolverOptions> planPreviews(const MethodSpec& spec, std::size_t elements,
  const SolverOptions& options, double finalSeconds, const ProgressionPlan& plan)
{
  std::vector<SolverOptions> previews;
  const double work = spec.sampleWork(elements, options);
  if (!(work > 0.0) || (finalSeconds >= 0.0 && finalSeconds < kPreviewWorthBudgets * plan.budgetSeconds))
  {
    return previews;
  }
  double fraction = plan.previewRate > 0.0 ? plan.budgetSeconds / (plan.previewRate * work) : kFirstPreviewFraction;
  double spent = 0.0;        // predicted seconds of the coarse solutions so far
  double previousWork = 0.0; // the last one's work
  for (; fraction <= kPreviewLargest; fraction *= kPreviewGrowth)
  {
    SolverOptions coarse = spec.coarser(options, fraction);
    // Few samples per vertex are noisy, and the final replaces this solution: smooth it.
    coarse.smoothing = true;
    // One shadow ray per vertex and light, not five: the oversampling only smooths shadow
    // edges, which the coarse indirect light cannot show, and it was a third of a first
    // stage's time on a large surface. The final traces its own.
    coarse.lightOversampling = false;
    const double coarseWork = spec.sampleWork(elements, coarse);
    if (!(coarseWork < work))
    {
      break; // the method has no coarser sampling at these options
    }
    if (coarseWork <= previousWork)
    {
      continue; // clamped to the same sampling as the last one
    }
    const double seconds = plan.previewRate * coarseWork;
    // Later stages only where the final is known to be long enough to afford them all.
    if (!previews.empty() &&
      (plan.previewRate <= 0.0 || finalSeconds < 0.0 || spent + seconds > kPreviewShare * finalSeconds))
    {
      break;
    }
    spent += seconds;
    previousWork = coarseWork;
    previews.push_back(std::move(coarse));
  }
  return previews;
}
}
