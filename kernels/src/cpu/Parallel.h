// One dispatch point for data-parallel loops on the CPU.
#pragma once

#include "linkgi/SolverTypes.h" // ProgressCallback

#include <atomic>
#include <cstddef>
#include <functional>

namespace linkgi
{
/// Runs body(begin, end) over [0, n) on all cores, in ranges of at least `grain` items.
void parallelRanges(std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body);

/// The smallest i in [0, n) with bad(i), or n where there is none, on all cores: a range
/// stops at the first index it finds, or once a smaller one is known. For the checks of a
/// large mesh's arrays, which find nothing as a rule and report the first offender.
template <typename Predicate>
std::size_t firstIndexWhere(std::size_t n, std::size_t grain, const Predicate& bad)
{
  std::atomic<std::size_t> first{ n };
  parallelRanges(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end && i < first.load(std::memory_order_relaxed); ++i)
    {
      if (bad(i))
      {
        std::size_t known = first.load(std::memory_order_relaxed);
        while (i < known && !first.compare_exchange_weak(known, i, std::memory_order_relaxed))
        {
        }
        return;
      }
    }
  });
  return first.load();
}

/// How many sequential slices parallelFor cuts [0, n) into: enough for a smooth progress bar
/// and a prompt abort (up to 32), few enough that the synchronisation between them costs
/// nothing measurable (at least 8 grains each).
std::size_t progressSlices(std::size_t n, std::size_t grain);

/// Like parallelRanges, cut into progressSlices sequential slices; `progress` is asked between
/// slices (on the calling thread, so it may touch GUI or VTK state) and can abort the loop.
void parallelFor(const char* stage, std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body,
  const ProgressCallback& progress);

/// Number of worker threads the loops use.
int workerCount();

/// Runs f() with the parallel loops inside it limited to `threads` workers (at least 1), so
/// a background solve can leave cores to the render loop.
void runWithConcurrency(int threads, const std::function<void()>& f);
}
