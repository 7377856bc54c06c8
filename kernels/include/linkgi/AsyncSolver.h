// Background updates: a worker thread solves while the caller keeps drawing the last result.
#pragma once

#include "linkgi/Resolution.h"
#include "linkgi/Solver.h"

#include <functional>
#include <memory>

namespace linkgi
{
/// One finished update, immutable once published.
struct AsyncResult
{
  std::uint64_t request = 0; ///< the id request() returned for the scene this solves
  /// Progressive updates: this is stage `stage` of the `stages` the request publishes (1 of
  /// 1 without previews); only the last is the request's final solution.
  std::uint32_t stage = 1, stages = 1;
  bool final() const { return stage == stages; }
  Solution solution;
  SolverStats stats;
};

/// Which stage of a progressive update is being solved (1 of 1 when there are no previews).
struct AsyncStage
{
  std::uint32_t stage = 0, stages = 0; ///< 0 of 0 while idle
};

/// Owns a ResolvedSolver and a worker thread. request() hands the worker a new scene and returns at
/// once; the worker publishes each finished solution as a new immutable AsyncResult, swapped
/// in atomically, so latest() never waits for a computation and never sees a mix of two
/// requests. Requests never queue up: a new request replaces the one waiting, so the worker
/// always goes on with the newest scene.
///
/// Whether a new request also aborts the update already running is a policy
/// (setAbortRunning). Aborting gives the lowest latency for a single change, but under
/// continuous change (a dragged light, an animation) every update is aborted before it ends
/// and nothing is ever shown: linkgi-live --benchmark measured 0 updates/s for the deforming
/// torso that way. So by default the running update finishes (a result is at most two
/// update times old) and only cancel() aborts it.
///
/// Sharing the machine with the render loop (Linux): each update runs on a thread of its own
/// at nice 10, except a progressive update's first coarse stage, which runs at the priority
/// of the thread that made the solver (the render loop's): it is short (setFirstStageSeconds)
/// and what the user waits for. Under continuous change (a request less than a second after the previous one:
/// an orbit with a camera-following light, a dragged light) the update runs in the idle
/// scheduling class (SCHED_IDLE) instead, so every frame the render loop draws preempts it at
/// once; on a two-core machine that is what keeps an orbit's frame time close to one without
/// global illumination, for fewer global-illumination updates per second while it lasts. Once
/// the changes stop (no request for a second) an idle-class update that still gets less than
/// half a core (another program keeps the cores busy) is moved to nice 10 and goes on, where
/// the process may do that (root, CAP_SYS_NICE, an RLIMIT_NICE of 10 or more); an unprivileged
/// thread cannot leave the idle class, so there it is aborted at its next progress check and
/// run again at nice 10 on a new thread. Either way it never starves.
/// setYieldToInteraction(false) keeps every update at nice 10.
///
/// Progressive updates (setProgressive): an update whose final solution is predicted to take
/// long first solves and publishes one or more coarse solutions of the same light (fewer
/// rays, VPLs, photons or bins: the method's own MethodSpec::coarser), the first one aimed at
/// setFirstStageSeconds() of work on this machine, and then the final solution, which is the
/// one a non-progressive update publishes, bit for bit. The coarse solutions are solved by
/// the final's solver, so the final reuses what does not depend on the sampling (the
/// surface's structures, the direct light). How long the final takes is
/// predicted from the time each of its stale stages took the last time it ran (or, where this
/// solver has not run it, from this process's last update of the method that ran every
/// stage), and the coarse sampling from the time the last first coarse solution of the method
/// took in this process; before any was measured, a coarse solution samples 1/32 of the work. A new request dropped the stages
/// still to come of the one before: it starts again from its own coarse stage. Under
/// continuous change no coarse stages are solved (they would flicker between the final
/// ones). See Documentation/Engine.md, "Progressive updates".
///
/// Temporal blending (optional): with blend factor a in (0, 1], the indirect irradiance is
/// published as a * new + (1 - a) * previous per element when the element count is
/// unchanged (radiance follows), which damps frame-to-frame flicker of the sampled indirect
/// light under a moving light or mesh at the cost of a short lag. Direct light is exact and
/// never blended, so shadows follow a moving light at once.
class AsyncSolver
{
public:
  /// `workerThreads` caps the threads the solve uses (0 = all cores but one), leaving the
  /// remaining core to the render loop.
  explicit AsyncSolver(int workerThreads = 0);
  ~AsyncSolver(); ///< cancels the running update and joins the worker
  AsyncSolver(const AsyncSolver&) = delete;
  AsyncSolver& operator=(const AsyncSolver&) = delete;

  /// Asks for `scene` to be solved at `resolution` (as given, through a proxy, or through a
  /// proxy the memory budget chooses for a surface it refuses; refinement is refused here,
  /// checkResolution); returns the request's id (1, 2, ...). Asking again for the same
  /// scene and options as the last request, while that one is pending, running or
  /// published, returns its id and starts nothing (and copies nothing: a render loop asks
  /// at every frame). A new scene is copied once. Through a proxy no coarse stages are
  /// solved: the proxy is the coarse solution.
  std::uint64_t request(const Scene& scene, const SolverOptions& options = {},
    const ResolutionOptions& resolution = {});
  /// The newest published result, or null before the first one. Never blocks on the worker.
  std::shared_ptr<const AsyncResult> latest() const;
  /// Aborts the running update and drops a pending request; latest() is unchanged.
  void cancel();
  /// True while a request is pending or being solved.
  bool busy() const;
  /// The id of the request being solved, 0 when the worker is idle or waiting.
  std::uint64_t solving() const;
  /// The fraction of the update being solved that is done, in [0, 1] (0 while idle): the
  /// solver's own progress, for progress bars.
  double progress() const;
  /// The stage of the update being solved (0 of 0 while idle).
  AsyncStage stage() const;
  /// Blocks until the final solution of `request` (or a newer request) has been published,
  /// the worker went idle without publishing it (superseded, cancelled or failed), or
  /// `timeoutSeconds` passed. Returns true if a final result for `request` or newer is
  /// available.
  bool wait(std::uint64_t request, double timeoutSeconds = 1e9) const;
  /// Error message of the newest request that failed (empty if none).
  std::string lastError() const;

  /// Blend factor for temporal stability, in (0, 1]; 1 (default) publishes results as they are.
  void setBlend(float factor);
  /// Publish coarse solutions before the final one where it is predicted to take long
  /// (default false, see above).
  void setProgressive(bool progressive);
  /// Seconds of work the first coarse solution aims at (default 0.5; at least 0.01).
  void setFirstStageSeconds(double seconds);
  /// Forgets the times this process measured (what plans the progressive stages of every
  /// AsyncSolver in it), as in a new process: for benchmarks and tests.
  static void forgetMeasurements();
  /// Let a new request abort the running update (default false, see above).
  void setAbortRunning(bool abort);
  /// Run updates under continuous change in the idle scheduling class (default true, see
  /// above; Linux only, elsewhere updates always run at the lower priority).
  void setYieldToInteraction(bool yield);
  /// True while the running update is in the idle scheduling class and not found starving
  /// (from then on it runs at nice 10, or is being stopped to run again there).
  bool yielding() const;
  /// Called on the update's thread after each publish (e.g. to wake a render loop).
  void setOnPublish(std::function<void(std::uint64_t request)> callback);

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
}
