#include "engine/WorkerThreads.h"

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>
#endif

namespace linkgi::engine
{
long threadId()
{
#ifdef __linux__
  return static_cast<long>(syscall(SYS_gettid));
#else
  return 0;
#endif
}

bool lowerPriority(bool idle)
{
#ifdef __linux__
  if (idle)
  {
    sched_param none{};
    if (pthread_setschedparam(pthread_self(), SCHED_IDLE, &none) == 0)
    {
      return true;
    }
  }
  setpriority(PRIO_PROCESS, static_cast<id_t>(threadId()), 10);
#else
  (void)idle;
#endif
  return false;
}

bool raiseFromIdle(std::thread& thread, long tid)
{
#ifdef __linux__
  sched_param none{};
  if (tid <= 0 || pthread_setschedparam(thread.native_handle(), SCHED_OTHER, &none) != 0)
  {
    return false;
  }
  setpriority(PRIO_PROCESS, static_cast<id_t>(tid), 10);
  return true;
#else
  (void)thread;
  (void)tid;
  return false;
#endif
}

void nameThread(const char* name)
{
#ifdef __linux__
  pthread_setname_np(pthread_self(), name);
#else
  (void)name;
#endif
}

double cpuSeconds(std::thread& thread)
{
#ifdef __linux__
  clockid_t clock;
  timespec t;
  if (pthread_getcpuclockid(thread.native_handle(), &clock) == 0 && clock_gettime(clock, &t) == 0)
  {
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
#else
  (void)thread;
#endif
  return -1.0;
}
}
