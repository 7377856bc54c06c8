#include "cpu/Parallel.h"

#include "linkgi/Error.h"

#if LINKGI_HAVE_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#else
#include "cpu/ThreadPool.h"
#endif

#include <algorithm>

namespace linkgi
{
#if LINKGI_HAVE_TBB
void parallelRanges(std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body)
{
  if (n == 0)
  {
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(grain, 1)),
    [&body](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}
#else
namespace
{
// Without TBB (the GPU machine): a pool of threads started once (ThreadPool.cpp).
thread_local int concurrencyLimit = 0;
}

void parallelRanges(std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body)
{
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t chunks = (n + grain - 1) / grain;
  if (chunks <= 1)
  {
    if (n)
    {
      body(0, n);
    }
    return;
  }
  const int helpers = int(std::min<std::size_t>(chunks, workerCount())) - 1;
  detail::runChunks(chunks, helpers,
    [&](std::size_t c) { body(c * grain, std::min(n, (c + 1) * grain)); });
}
#endif

std::size_t progressSlices(std::size_t n, std::size_t grain)
{
  return std::min<std::size_t>(32, std::max<std::size_t>(1, n / (grain * 8)));
}

void parallelFor(const char* stage, std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body,
  const ProgressCallback& progress)
{
  if (!progress)
  {
    parallelRanges(n, grain, body);
    return;
  }
  const std::size_t slices = progressSlices(n, grain);
  for (std::size_t s = 0; s < slices; ++s)
  {
    if (!progress(stage, static_cast<double>(s) / slices))
    {
      throw Aborted();
    }
    const std::size_t begin = n * s / slices, end = n * (s + 1) / slices;
    parallelRanges(end - begin, grain,
      [&body, begin](std::size_t b, std::size_t e) { body(begin + b, begin + e); });
  }
  if (!progress(stage, 1.0))
  {
    throw Aborted();
  }
}

#if LINKGI_HAVE_TBB
int workerCount()
{
  return tbb::this_task_arena::max_concurrency();
}

void runWithConcurrency(int threads, const std::function<void()>& f)
{
  tbb::task_arena arena(std::max(1, threads));
  arena.execute(f);
}
#else
int workerCount()
{
  const int all = detail::poolConcurrency();
  return concurrencyLimit > 0 ? std::min(concurrencyLimit, all) : all;
}

void runWithConcurrency(int threads, const std::function<void()>& f)
{
  const int previous = concurrencyLimit;
  concurrencyLimit = std::max(1, threads);
  try
  {
    f();
  }
  catch (...)
  {
    concurrencyLimit = previous;
    throw;
  }
  concurrencyLimit = previous;
}
#endif
}
