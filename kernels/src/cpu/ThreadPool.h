// The worker threads of builds without TBB (the GPU machine): started once, so a parallel
// loop costs a wake-up instead of creating threads (which took longer than a light update's
// host work). Private to Parallel.cpp.
#pragma once

#include <cstddef>
#include <functional>

namespace linkgi::detail
{
/// Runs chunk(c) for c in [0, chunks) on the calling thread and up to `helpers` pool
/// threads; returns when all are done, rethrowing the first exception. A call while the
/// pool is busy (another thread's loop, or a loop inside a chunk) runs on the caller alone.
void runChunks(std::size_t chunks, int helpers, const std::function<void(std::size_t)>& chunk);

/// Threads of the pool plus the caller.
int poolConcurrency();
}
