#include "linkgi/AsyncSolver.h"

#include "engine/Pipeline.h"
#include "engine/Progression.h"
#include "engine/WorkerThreads.h"

#include "cuda/Cuda.h"
#include "linkgi/Error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

namespace linkgi
{
namespace
{
using Clock = std::chrono::steady_clock;

/// Requests closer together than this are one continuous change (an orbit, a dragged light).
constexpr std::chrono::milliseconds kContinuous{ 1000 };
/// How often the worker checks that an idle-class update is not starving.
constexpr std::chrono::milliseconds kStarvationWindow{ 500 };
}

struct AsyncSolver::Impl
{
  struct Request
  {
    std::uint64_t id;
    std::shared_ptr<const Scene> scene; // shared by lastAccepted and pending
    SolverOptions options;
    ResolutionOptions resolution;
  };

  ResolvedSolver solver; // touched by the worker only
  int threads = 1;
  // Progressive updates, touched by the worker only: what the final stages took and the
  // input they took it on. The coarse stages run on `solver` too, so the final reuses what
  // they computed that the sampling does not touch.
  engine::StageHistory history;
  std::shared_ptr<const Scene> finalScene;
  SolverOptions finalOptions;
  int gpus = -1; // CUDA devices, asked once (-1: not yet)
  std::optional<Request> lastAccepted; // for repeated identical requests

  mutable std::mutex mutex;
  mutable std::condition_variable changed;
  std::optional<Request> pending;
  std::uint64_t nextId = 1;
  std::uint64_t running = 0; // id being solved, 0 when idle
  double progress = 0.0;     // fraction of the running stage done
  AsyncStage stage;          // ... of the running update
  bool progressive = false;
  double firstStageSeconds = 0.5;
  bool stopping = false;
  Clock::time_point lastRequestAt; // when the newest request was accepted
  bool continuous = false;         // it came less than kContinuous after the one before
  bool yieldToInteraction = true;
  bool idleClass = false; // the running update is in the idle scheduling class
  long updateTid = 0;     // ... on this kernel thread
  bool starved = false;   // ... and is to stop, to be run again at nice 10
  bool solved = false;    // the update thread is done
  std::shared_ptr<const AsyncResult> published;
  std::string error;
  float blend = 1.f;
  bool abortRunning = false;
  std::function<void(std::uint64_t)> onPublish;
  std::thread worker;

  void run();
  bool solveOnThread(Request& request, bool idle);
  /// `lowerLater`: the thread still runs at its creator's priority, and lowers itself to
  /// nice 10 after the first coarse stage (or before the first stage, if that is the final).
  void solve(Request& request, bool lowerLater);
  std::vector<SolverOptions> plan(const Request& request);
  /// Publishes stage `stage` of `stages` of `request`; the final one also leaves the worker
  /// idle with it, and records its times, with those of the stages it left to `coarse` (the
  /// request's first coarse stage; null: none).
  void publish(const Request& request, std::uint32_t index, std::uint32_t stages, const Solution& solution,
    const SolverStats& stats, bool throughProxy, const SolverStats* coarse);
  /// The result to publish: `s` itself, or for a final solution after a final one, blended.
  std::shared_ptr<AsyncResult> blended(const Request& request, bool final, const Solution& s, const SolverStats& st);
};

AsyncSolver::AsyncSolver(int workerThreads) : impl(std::make_unique<Impl>())
{
  impl->threads = workerThreads > 0
    ? workerThreads
    : std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1);
  impl->worker = std::thread([this] { impl->run(); });
}

AsyncSolver::~AsyncSolver()
{
  {
    std::lock_guard<std::mutex> lock(impl->mutex);
    impl->stopping = true;
    impl->pending.reset();
  }
  impl->changed.notify_all();
  impl->worker.join();
}

std::uint64_t AsyncSolver::request(const Scene& scene, const SolverOptions& options,
  const ResolutionOptions& resolution)
{
  checkResolution(options, resolution, true);
  std::uint64_t id;
  {
    std::lock_guard<std::mutex> lock(impl->mutex);
    // Asking again for what is already pending, running or published is not new work: a
    // render loop may re-request the same scene every frame.
    const auto& last = impl->lastAccepted;
    if (last && last->options == options && last->resolution == resolution && sameScene(*last->scene, scene) &&
      (impl->pending || impl->running == last->id ||
        (impl->published && impl->published->request == last->id)))
    {
      return last->id;
    }
    id = impl->nextId++;
    const Clock::time_point now = Clock::now();
    impl->continuous = id > 1 && now - impl->lastRequestAt < kContinuous;
    impl->lastRequestAt = now;
    impl->lastAccepted = Impl::Request{ id, std::make_shared<const Scene>(scene), options, resolution };
    impl->pending = impl->lastAccepted;
  }
  impl->changed.notify_all();
  return id;
}

std::shared_ptr<const AsyncResult> AsyncSolver::latest() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->published;
}

void AsyncSolver::cancel()
{
  {
    std::lock_guard<std::mutex> lock(impl->mutex);
    impl->pending.reset();
    impl->running = impl->running ? ~std::uint64_t(0) : 0; // marks the running one superseded
  }
  impl->changed.notify_all();
}

bool AsyncSolver::busy() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->pending.has_value() || impl->running != 0;
}

std::uint64_t AsyncSolver::solving() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->running == ~std::uint64_t(0) ? 0 : impl->running;
}

double AsyncSolver::progress() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->running == 0 || impl->running == ~std::uint64_t(0) ? 0.0 : impl->progress;
}

void AsyncSolver::forgetMeasurements()
{
  engine::forgetRates();
}

AsyncStage AsyncSolver::stage() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->running == 0 || impl->running == ~std::uint64_t(0) ? AsyncStage{} : impl->stage;
}

bool AsyncSolver::wait(std::uint64_t request, double timeoutSeconds) const
{
  std::unique_lock<std::mutex> lock(impl->mutex);
  const auto finalFor = [&] {
    const auto& p = impl->published;
    return p && (p->request > request || (p->request == request && p->final()));
  };
  const auto done = [&] { return finalFor() || (!impl->pending && impl->running == 0); };
  impl->changed.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), done);
  return finalFor();
}

std::string AsyncSolver::lastError() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->error;
}

void AsyncSolver::setBlend(float factor)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->blend = std::clamp(factor, 1e-3f, 1.f);
}

void AsyncSolver::setProgressive(bool progressive)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->progressive = progressive;
}

void AsyncSolver::setFirstStageSeconds(double seconds)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->firstStageSeconds = std::isfinite(seconds) ? std::max(0.01, seconds) : 0.5;
}

void AsyncSolver::setAbortRunning(bool abort)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->abortRunning = abort;
}

void AsyncSolver::setYieldToInteraction(bool yield)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->yieldToInteraction = yield;
}

bool AsyncSolver::yielding() const
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  return impl->running != 0 && impl->idleClass && !impl->starved;
}

void AsyncSolver::setOnPublish(std::function<void(std::uint64_t)> callback)
{
  std::lock_guard<std::mutex> lock(impl->mutex);
  impl->onPublish = std::move(callback);
}

void AsyncSolver::Impl::run()
{
  // This thread takes the requests and watches the update threads; each update runs on a
  // thread of its own (solveOnThread), at the priority of its own (see the class comment).
  // It keeps its creator's priority (it only waits), which its update threads inherit: a
  // thread may lower its own priority but, unprivileged, never raise it again.
  engine::nameThread("linkgi-watch");
  for (;;)
  {
    Request request;
    bool idle;
    {
      std::unique_lock<std::mutex> lock(mutex);
      changed.wait(lock, [this] { return stopping || pending.has_value(); });
      if (stopping)
      {
        return;
      }
      request = std::move(*pending);
      pending.reset();
      running = request.id;
      idle = yieldToInteraction && continuous;
    }
    while (solveOnThread(request, idle))
    {
      idle = false; // starved in the idle class: again at nice 10
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      running = 0;
    }
    changed.notify_all();
  }
}

bool AsyncSolver::Impl::solveOnThread(Request& request, bool idle)
{
  {
    std::lock_guard<std::mutex> lock(mutex);
    solved = false;
    starved = false;
    idleClass = false;
  }
  const auto update = [this, &request](bool inIdleClass, bool lowerLater) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      idleClass = inIdleClass;
      updateTid = engine::threadId();
    }
    solve(request, lowerLater);
    {
      std::lock_guard<std::mutex> lock(mutex);
      solved = true;
      idleClass = false;
    }
    changed.notify_all();
  };
  std::thread thread;
  try
  {
    thread = std::thread([&update, idle] {
      // Under continuous change the idle class from the start; otherwise solve() lowers
      // the thread once its first coarse stage, which the user waits for, is published.
      const bool inIdleClass = idle && engine::lowerPriority(true);
      engine::nameThread("linkgi-async");
      update(inIdleClass, !idle);
    });
  }
  catch (const std::system_error&) // no thread to be had: solve here, at nice 10
  {
    engine::lowerPriority(false);
    update(false, false);
    return false;
  }
  // An idle-class update gets no CPU while anything else wants it. That is the point while
  // the changes go on; once they stopped, an update that still gets under half a core is
  // moved to nice 10 where the process may, keeping its work, and else stopped (at its next
  // progress check, which a thread that gets a few thousandths of a core may reach only
  // once the other load ends) and run again at nice 10.
  std::unique_lock<std::mutex> lock(mutex);
  double cpuBefore = engine::cpuSeconds(thread);
  Clock::time_point before = Clock::now();
  while (!changed.wait_for(lock, kStarvationWindow, [this] { return solved; }))
  {
    const Clock::time_point now = Clock::now();
    const double cpu = engine::cpuSeconds(thread);
    const double share = (cpu - cpuBefore) / std::chrono::duration<double>(now - before).count();
    if (idleClass && cpuBefore >= 0.0 && cpu >= 0.0 && now - lastRequestAt > kContinuous && share < 0.5)
    {
      if (engine::raiseFromIdle(thread, updateTid))
      {
        idleClass = false;
      }
      else
      {
        starved = true;
      }
    }
    cpuBefore = cpu;
    before = now;
  }
  const bool again = starved && running == request.id && !stopping;
  lock.unlock();
  thread.join();
  return again;
}

std::vector<SolverOptions> AsyncSolver::Impl::plan(const Request& request)
{
  engine::ProgressionPlan settings;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!progressive || continuous)
    {
      return {};
    }
    settings.budgetSeconds = firstStageSeconds;
  }
  if (request.resolution.proxyVertices != 0 || solver.proxyVertices() != 0)
  {
    return {}; // the proxy is the coarse solution (and the surface may not fit the budget)
  }
  const SolverOptions& options = request.options;
  const engine::MethodSpec& spec = engine::methodSpec(options.method);
  const std::size_t elements = engine::elementCount(*request.scene, options);
  // Predicted from this solver's stages where it ran this method and backend, else from the
  // process's full updates; unknown (negative) before either.
  const double fullRate = engine::measuredRate(engine::RateOf::FullUpdate, options);
  double finalSeconds = fullRate > 0.0 ? fullRate * spec.sampleWork(elements, options) : -1.0;
  if (finalScene && finalOptions.method == options.method && finalOptions.backend == options.backend)
  {
    const engine::Changes changes = engine::changesBetween(*request.scene, options, *finalScene, finalOptions);
    finalSeconds = history.predictSeconds(
      engine::staleStages(spec.stages(), changes), engine::historyWork(spec, elements, options));
  }
  if (finalSeconds < 0.0 && options.backend != Backend::Cpu)
  {
    // Unknown on a GPU: a GPU solves the default sampling of a mesh of 150k vertices in
    // 0.03-0.3 s, while a coarse stage's own start (its structures, their upload) took
    // 0.1-0.25 s there: the coarse stage would only delay the final.
    if (gpus < 0)
    {
      gpus = cuda::compiled() ? static_cast<int>(cuda::devices().size()) : 0;
    }
    if (gpus > 0)
    {
      return {};
    }
  }
  settings.previewRate = engine::measuredRate(engine::RateOf::FirstCoarseStage, options);
  return engine::planPreviews(spec, elements, options, finalSeconds, settings);
}

void AsyncSolver::Impl::solve(Request& request, bool lowerLater)
{
  // The update stops at its next progress check after cancel() or the destructor, and, with
  // setAbortRunning(true), once a newer request is waiting, or once it starved.
  const ProgressCallback stillWanted = [this, id = request.id](const char*, double fraction) {
    std::lock_guard<std::mutex> lock(mutex);
    progress = std::max(progress, fraction);
    return !stopping && !starved && running == id && !(abortRunning && pending.has_value());
  };
  try
  {
    const std::vector<SolverOptions> previews = plan(request);
    const auto stages = static_cast<std::uint32_t>(previews.size() + 1);
    std::optional<SolverStats> firstCoarse;
    for (std::uint32_t s = 1; s <= stages; ++s)
    {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (s > 1 && (stopping || running != request.id || pending.has_value()))
        {
          running = 0; // a newer request starts again from its own first stage
          return;
        }
        progress = 0.0;
        stage = AsyncStage{ s, stages };
      }
      // A first coarse stage runs at the priority of the thread that asked for the update
      // (the render loop's): it is short (firstStageSeconds of work) and what the user waits
      // for, and at nice 10 a render loop drawing meanwhile left it a tenth of a core. The
      // rest, the final's long work, runs at nice 10 beside the render loop.
      if (lowerLater && !(s == 1 && s < stages))
      {
        engine::lowerPriority(false);
        lowerLater = false;
      }
      if (s == stages)
      {
        runWithConcurrency(threads,
          [&] { solver.update(*request.scene, request.options, request.resolution, stillWanted); });
        publish(request, s, stages, solver.solution(), solver.stats(), solver.proxyVertices() != 0,
          firstCoarse ? &*firstCoarse : nullptr);
        return;
      }
      const SolverOptions& coarse = previews[s - 1];
      const auto start = Clock::now();
      try
      {
        runWithConcurrency(threads, [&] { solver.updateCoarse(*request.scene, coarse, stillWanted); });
      }
      catch (const OutOfMemoryBudget&)
      {
        // The surface is over the budget even coarsely: the final stage goes through the
        // proxy the budget chooses (ResolvedSolver), with no coarse stage before it.
        s = stages - 1;
        continue;
      }
      if (s == 1)
      {
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        const double work = engine::methodSpec(coarse.method).sampleWork(engine::elementCount(*request.scene, coarse), coarse);
        engine::recordRate(engine::RateOf::FirstCoarseStage, coarse, seconds / work);
        firstCoarse = solver.stats(); // the stages the later ones reuse ran here
      }
      publish(request, s, stages, solver.solution(), solver.stats(), false, nullptr);
    }
  }
  catch (const Aborted&)
  {
  }
  catch (const std::exception& e)
  {
    std::lock_guard<std::mutex> lock(mutex);
    error = e.what();
    running = 0; // with the error: busy() and lastError() never disagree
  }
}

void AsyncSolver::Impl::publish(const Request& request, std::uint32_t index, std::uint32_t stages,
  const Solution& solution, const SolverStats& stats, bool throughProxy, const SolverStats* coarse)
{
  std::shared_ptr<AsyncResult> result = blended(request, index == stages, solution, stats);
  result->stage = index;
  result->stages = stages;
  if (result->final() && !throughProxy) // a proxy's times are not the surface's
  {
    const SolverOptions& o = request.options;
    const engine::MethodSpec& spec = engine::methodSpec(o.method);
    const std::size_t elements = engine::elementCount(*request.scene, o);
    // What the update would have taken alone: with the stages it left to its coarse stage.
    const SolverStats measured = coarse ? engine::withStagesOf(stats, *coarse) : stats;
    history.record(spec, measured, engine::historyWork(spec, elements, o));
    const bool full = std::all_of(spec.stages().begin(), spec.stages().end(),
      [&](const engine::StageSpec& st) { return measured.ran(st.name); });
    const double work = spec.sampleWork(elements, o);
    if (full && work > 0.0)
    {
      engine::recordRate(engine::RateOf::FullUpdate, o, 1e-3 * measured.msTotal / work);
    }
    finalScene = request.scene;
    finalOptions = o;
  }
  std::function<void(std::uint64_t)> callback;
  {
    std::lock_guard<std::mutex> lock(mutex);
    published = std::move(result);
    error.clear();
    if (index == stages)
    {
      // Idle with the final result, in one step: a caller that saw it never sees busy().
      running = 0;
    }
    callback = onPublish;
  }
  changed.notify_all();
  if (callback)
  {
    callback(request.id);
  }
}

std::shared_ptr<AsyncResult> AsyncSolver::Impl::blended(
  const Request& request, bool final, const Solution& s, const SolverStats& st)
{
  auto result = std::make_shared<AsyncResult>();
  result->request = request.id;
  result->solution = s;
  result->stats = st;
  std::shared_ptr<const AsyncResult> previous;
  float a;
  {
    std::lock_guard<std::mutex> lock(mutex);
    previous = published;
    a = blend;
  }
  // A coarse stage is shown as it is, and a final one is never blended with one.
  if (a >= 1.f || !final || !previous || !previous->final() ||
    previous->solution.elementCount() != s.elementCount())
  {
    return result;
  }
  // Only the indirect light is blended: it carries the sampling noise, while direct light is
  // exact and must follow a moving light without lag. Radiance follows the blended value.
  const std::size_t nv = request.scene->vertexCount();
  Solution& out = result->solution;
  for (std::size_t e = 0; e < out.elementCount(); ++e)
  {
    const Vec3f before = previous->solution.indirect[e];
    const Vec3f mixed = out.indirect[e] * a + before * (1.f - a);
    out.radiance[e] += request.scene->albedo[e % nv] * (mixed - out.indirect[e]) * (1.f / kPi);
    out.indirect[e] = mixed;
  }
  return result;
}
}
