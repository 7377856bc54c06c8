// The memory budget: the one place that decides whether an update may run on the memory the
// machine has. The method estimates (MethodSpec::estimateMemory), this compares and explains.
#pragma once

#include "engine/Pipeline.h"
#include "linkgi/Memory.h"

namespace linkgi::engine
{
/// What the budget says about one update.
struct MemoryVerdict
{
  MemoryEstimate estimate; ///< the method's estimate for the stale stages
  std::uint64_t budget = 0; ///< host bytes the update may use
  bool fits = true;
  /// When it does not fit: the most rays per vertex (a perfect square below the requested)
  /// that fit this mesh, 0 when none or the estimate does not depend on them; and the most
  /// vertices (triangles in proportion) that fit at the requested rays, 0 when none.
  std::uint32_t raysThatFit = 0;
  std::uint64_t verticesThatFit = 0;
};

/// Judges the stages `stale` of `spec` on a mesh of `shape` under `budget` host bytes.
MemoryVerdict judgeMemory(const MethodSpec& spec, const MemoryShape& shape,
  const SolverOptions& options, std::uint32_t stale, bool cuda, std::uint64_t budget);

/// Before a backend runs the stages `stale`: records the estimate and the budget
/// (options.memoryBudget, or what is available less a margin) in `stats`, and throws
/// OutOfMemoryBudget saying what would fit when the estimate is over the budget. The
/// solution has not been written at that point, so the previous result stays. With `first`,
/// only the stages `stale & first` are judged now (those before a method samples its
/// memory; it is judged again then); a refusal still says what would fit the whole update.
/// Under MPI (options.partition) a collective step: each process judges its own estimate
/// under its own budget, and every process refuses when one does, with the smallest mesh
/// that fits them all.
void checkMemoryBudget(const MethodSpec& spec, const MemoryShape& shape, const SolverOptions& options,
  std::uint32_t stale, bool cuda, SolverStats& stats, std::uint32_t first = ~0u);

/// What the budget (as checkMemoryBudget recorded it in `stats`) leaves beyond `held` bytes:
/// the most that a stage holding them may allocate for what only tracing can tell (a second
/// pass of light paths). UINT64_MAX when no budget was recorded.
std::uint64_t memoryLeft(const SolverStats& stats, std::uint64_t held);

/// Raises the update's estimate in `stats` to `bytes` where that is more: what a stage found
/// it holds at once (`held` and what it allocated beyond it).
void raiseEstimate(SolverStats& stats, std::uint64_t bytes);
}
