#include "cpu/ThreadPool.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace linkgi::detail
{
namespace
{
/// Set while a thread runs chunks: a loop inside a chunk runs serially (a std::mutex must
/// not be locked again by its owner, and the pool's threads are taken anyway).
thread_local bool insideChunk = false;

class Pool
{
public:
  static Pool& instance()
  {
    static Pool pool;
    return pool;
  }

  int size() const { return int(workers.size()); }

  void run(std::size_t chunks, int helpers, const std::function<void(std::size_t)>& chunk)
  {
    std::unique_lock<std::mutex> owner(busy, std::defer_lock);
    if (insideChunk || helpers <= 0 || !owner.try_lock())
    {
      for (std::size_t c = 0; c < chunks; ++c)
      {
        chunk(c);
      }
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      job = &chunk;
      total = chunks;
      next = 0;
      seats = helpers;
      open = true;
      error = nullptr;
      ++generation;
    }
    wake.notify_all();
    work();
    std::unique_lock<std::mutex> lock(mutex);
    open = false; // no one joins any more; wait for those who did
    finished.wait(lock, [this] { return participants == 0; });
    job = nullptr;
    if (error)
    {
      std::rethrow_exception(error);
    }
  }

private:
  Pool()
  {
    const int helpers = std::max(0, int(std::thread::hardware_concurrency()) - 1);
    for (int i = 0; i < helpers; ++i)
    {
      workers.emplace_back([this] { loop(); });
    }
  }

  ~Pool()
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    wake.notify_all();
    for (std::thread& t : workers)
    {
      t.join();
    }
  }

  void loop()
  {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex);
    for (;;)
    {
      wake.wait(lock, [&] { return stop || (generation != seen && open && seats > 0); });
      if (stop)
      {
        return;
      }
      seen = generation;
      --seats;
      ++participants;
      lock.unlock();
      work();
      lock.lock();
      if (--participants == 0)
      {
        finished.notify_all();
      }
    }
  }

  void work()
  {
    insideChunk = true;
    for (std::size_t c = next++; c < total; c = next++)
    {
      try
      {
        (*job)(c);
      }
      catch (...)
      {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (!error)
        {
          error = std::current_exception();
        }
        next = total;
      }
    }
    insideChunk = false;
  }

  std::vector<std::thread> workers;
  std::mutex busy; ///< one loop at a time
  std::mutex mutex, errorMutex;
  std::condition_variable wake, finished;
  const std::function<void(std::size_t)>* job = nullptr;
  std::size_t total = 0;
  std::atomic<std::size_t> next{ 0 };
  int seats = 0, participants = 0;
  bool open = false, stop = false;
  std::uint64_t generation = 0;
  std::exception_ptr error;
};
}

void runChunks(std::size_t chunks, int helpers, const std::function<void(std::size_t)>& chunk)
{
  Pool::instance().run(chunks, helpers, chunk);
}

int poolConcurrency()
{
  return Pool::instance().size() + 1;
}
}
