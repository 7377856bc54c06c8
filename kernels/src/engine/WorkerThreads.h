// How a background update's thread shares the machine (Linux; elsewhere they do nothing):
// its priority, the idle scheduling class, its name and the CPU time it got. AsyncSolver's.
#pragma once

#include <thread>

namespace linkgi::engine
{
/// The calling thread's kernel id (0 where there is none to tell).
long threadId();

/// Lowers the calling thread's priority: the idle scheduling class where `idle` is asked
/// for and allowed, nice 10 otherwise. Returns whether it is in the idle class.
bool lowerPriority(bool idle);

/// Moves `thread` (whose kernel id is `tid`) from the idle scheduling class to nice 10, where
/// the process may (root, CAP_SYS_NICE or an RLIMIT_NICE of 10 or more; an unprivileged
/// thread cannot leave the idle class). Returns whether it did.
bool raiseFromIdle(std::thread& thread, long tid);

/// Names the calling thread, so top, perf and gdb tell the threads apart.
void nameThread(const char* name);

/// CPU seconds `thread` has run, or a negative value where that is unknown.
double cpuSeconds(std::thread& thread);
}
