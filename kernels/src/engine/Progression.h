// Progressive updates: which coarser solutions an update publishes before its final one, and
// at what sampling, so that the first arrives after about a time budget (AsyncSolver; see
// Documentation/Engine.md, "Progressive updates"). Pure functions of what was measured, so
// the policy is tested without threads or timing.
#pragma once

#include "engine/Pipeline.h"

#include <cstdint>
#include <vector>

namespace linkgi::engine
{
/// The perfect square nearest below `fraction` * `square` (itself a perfect square), at least
/// `least` (a perfect square) and at most `square`: a coarser count of rays.
std::uint32_t scaledSquare(std::uint32_t square, double fraction, std::uint32_t least);
/// `fraction` * `count` rounded, at least `least` and at most `count`: a coarser sample count.
std::uint32_t scaledCount(std::uint32_t count, double fraction, std::uint32_t least);

/// What one backend's updates of one method took, stage by stage, as the progression
/// predicts the next update from: per stage of the method, its milliseconds (parts included)
/// the last time it ran and the work it ran with (0: never ran). The work is the method's
/// sampleWork(), or the element count where it has none.
struct StageHistory
{
  std::vector<double> ms;
  std::vector<double> work;
  /// Records the stages `stats` says ran, with work `work`.
  void record(const MethodSpec& spec, const SolverStats& stats, double work);
  /// Seconds the stages `stale` will take with work `work`, each scaled from its last run
  /// by the work (rays or VPLs scale the sampling, elements everything); negative when one
  /// of them never ran.
  double predictSeconds(std::uint32_t stale, double work) const;
};

/// `final`'s statistics plus the stages it left to `coarse`, a coarse stage of the same update
/// on the same solver: stages (and their parts) that ran there and not in `final`, with their
/// times added to msTotal. Those stages do not depend on the sampling, so this is what the
/// update would have taken alone: what its history and rates record.
SolverStats withStagesOf(const SolverStats& final, const SolverStats& coarse);

/// The work StageHistory scales by: `spec`'s sampleWork, or the element count.
double historyWork(const MethodSpec& spec, std::size_t elements, const SolverOptions& options);

/// The elements of `scene` solved with `options`: its vertices, and their back sides.
std::size_t elementCount(const Scene& scene, const SolverOptions& options);

/// What this process measured of the machine, shared by every AsyncSolver in it so that a
/// second dataset is planned as well as the first's later updates: seconds per unit of
/// sampling work (MethodSpec::sampleWork) per method and backend setting, of the last first
/// coarse stage (what a first stage is aimed by) and of the last final update that ran
/// every stage (what an update with nothing cached is predicted by). 0: not measured yet.
enum class RateOf
{
  FirstCoarseStage,
  FullUpdate
};
double measuredRate(RateOf kind, const SolverOptions& options);
void recordRate(RateOf kind, const SolverOptions& options, double secondsPerWork);
/// Forgets every measured rate, as in a new process.
void forgetRates();

/// The progression's settings and what it measured on this machine.
struct ProgressionPlan
{
  /// Seconds the first coarse solution should take.
  double budgetSeconds = 0.5;
  /// Seconds per unit of sampling work (MethodSpec::sampleWork) that the method's last coarse
  /// solution took, all stages included; 0 before one was measured.
  double previewRate = 0.0;
};

/// Before the first measurement the first coarse solution samples this fraction of the work
/// (the link method's 256 rays: 9, its least).
constexpr double kFirstPreviewFraction = 1.0 / 32.0;
/// A final update predicted to take less than this many budgets is published alone: a
/// coarse solution would arrive little earlier and delay it by a large share.
constexpr double kPreviewWorthBudgets = 4.0;
/// Coarse solutions after the first are each this many times its work, while all of them
/// together take at most kPreviewShare of the final update's predicted time.
constexpr double kPreviewGrowth = 4.0;
constexpr double kPreviewShare = 0.1;
/// A coarse solution of more than this fraction of the final's work is not worth its time.
constexpr double kPreviewLargest = 0.25;

/// The options of the coarse solutions to solve and publish before the final one, coarsest
/// first; empty: publish the final one alone. `finalSeconds` is the final update's predicted
/// time (negative: unknown, e.g. the first update of a mesh).
std::vector<SolverOptions> planPreviews(const MethodSpec& spec, std::size_t elements,
  const SolverOptions& options, double finalSeconds, const ProgressionPlan& plan);
}
