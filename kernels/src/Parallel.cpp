#include "linkgi/Parallel.h"

#include "linkgi/Error.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace linkgi
{
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

void parallelFor(const char* stage, std::size_t n, std::size_t grain,
  const std::function<void(std::size_t begin, std::size_t end)>& body,
  const ProgressCallback& progress)
{
  if (!progress)
  {
    parallelRanges(n, grain, body);
    return;
  }
  // Enough slices for a smooth progress bar and a prompt abort, few enough that the
  // synchronisation between them costs nothing measurable.
  const std::size_t slices = std::min<std::size_t>(32, std::max<std::size_t>(1, n / (grain * 8)));
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

int workerCount()
{
  return tbb::this_task_arena::max_concurrency();
}

void runWithConcurrency(int threads, const std::function<void()>& f)
{
  tbb::task_arena arena(std::max(1, threads));
  arena.execute(f);
}
}
