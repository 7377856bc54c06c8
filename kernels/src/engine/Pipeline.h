// The engine's shape: the orchestrator (Solver.cpp) runs a *method*'s stages on a *backend*.
// A method declares its stages and which input changes make each stale; a backend implements
// a method's stages and keeps their results between updates. The orchestrator alone decides
// what is stale, maps progress, times stages, counts runs, picks the backend and falls back
// to the CPU. See Documentation/Engine.md. Host-only: no device code, no CUDA headers.
#pragma once

#include "linkgi/Memory.h"
#include "cpu/Parallel.h"
#include "linkgi/SolverTypes.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkgi
{
class RayTracer;
}

namespace linkgi::engine
{
/// Milliseconds since `start`: what stages, parts and the orchestrator time themselves with.
inline double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// What differs between an update's input and the input of the last update the backend
/// completed: one bit per kind of change. A backend that never ran, was reset, or lost its
/// caches sees kEverything.
using Changes = std::uint32_t;
enum : Changes
{
  kTopology = 1u << 0,          ///< triangles or vertex count
  kPositions = 1u << 1,         ///< vertex positions
  kNormals = 1u << 2,           ///< vertex normals
  kLights = 1u << 3,            ///< the point, spot and directional lights
  kAlbedo = 1u << 4,            ///< rho
  kEmission = 1u << 5,          ///< Le of emissive surfaces
  kEnvironmentLayout = 1u << 6, ///< constant colour vs lat-long map, and the map's size
  kEnvironmentRadiance = 1u << 7, ///< the environment's colour or texels
  kSampling = 1u << 8,          ///< options: rays per vertex, twist, seed
  kSides = 1u << 9,             ///< options: two-sided elements
  kLightSampling = 1u << 10,    ///< options: light oversampling
  kIteration = 1u << 11,        ///< options: bounces
  kFiltering = 1u << 12,        ///< options: smoothing, feature angle
  kBackendSetup = 1u << 13,     ///< options: how the backend builds its structures (BVH build)
  kPlacement = 1u << 14,        ///< options: which backend, how many GPUs (no stage reads it)
  kMethodOptions = 1u << 15,    ///< options of one method (SolverOptions::instantRadiosity, ...)
  kGeometry = kTopology | kPositions | kNormals,
  kEverything = ~0u
};

/// Which bits differ between two inputs (both validated) and two option sets. Bits in
/// `knownSame` are not compared (the orchestrator lent those arrays from `before`).
Changes changesBetween(const Scene& now, const SolverOptions& optionsNow, const Scene& before,
  const SolverOptions& optionsBefore, Changes knownSame = 0);

/// One stage of a method, as the method declares it.
struct StageSpec
{
  const char* name;     ///< "Links": stats, field data (LinkGI.MsLinks), progress label
  const char* counter;  ///< lifetime run counter ("LinkBuilds"), "" for none
  Changes dependsOn;    ///< input changes that make it stale
  std::uint32_t after;  ///< bit i: stale whenever stage i re-runs (i < this stage)
  double progressShare; ///< its part of a full update's progress, in any unit
};

/// The stages that `changes` make stale, directly or through an upstream stage that re-runs:
/// bit i for stages[i].
std::uint32_t staleStages(const std::vector<StageSpec>& stages, Changes changes);

/// A stage's window on the update in progress.
class StageContext
{
public:
  StageContext(const Scene& scene, const SolverOptions& options, Changes changes,
    ProgressCallback progress, Solution& solution, SolverStats& stats, const char* stage)
    : scene(scene), options(options), changes(changes), progress(std::move(progress)),
      solution(solution), stats(stats), stageName(stage)
  {
  }
  const Scene& scene;
  const SolverOptions& options;
  /// Since this backend's last completed update; stages read it to skip unchanged uploads.
  const Changes changes;
  /// This stage's own progress in [0, 1], mapped onto its window of the update's bar.
  const ProgressCallback progress;
  /// Reports `fraction` of the stage done; throws Aborted if the caller asked to stop.
  void check(double fraction) const;
  /// The update's result, which the last stage writes (its buffers are those of the
  /// solution before last, so equal sizes need no allocation).
  Solution& solution;
  /// Records `ms` of this stage's time as the part `name` (e.g. "Compress" of "Links").
  void part(const char* name, double ms) const;
  /// For sizes and device details (rays, links, bvh builds, per-GPU profile).
  SolverStats& stats;

private:
  const char* stageName;
};

/// One backend's implementation of one method's stages, and their caches.
class MethodBackend
{
public:
  virtual ~MethodBackend() = default;
  /// Runs stage `index` of the method's stages(). Results a later update may reuse are
  /// staged until commit(). Throws Error, Aborted, or CudaError (the orchestrator then
  /// falls back to the CPU).
  virtual void run(std::size_t index, const StageContext& context) = 0;
  /// The update succeeded: staged results become the cache.
  virtual void commit() = 0;
  /// The update failed or was aborted. Returns true if the caches are still those of the
  /// last commit (the next update may reuse them), false if they are lost.
  virtual bool discard() = 0;
  /// After a commit: "cpu" / "cuda", what it ran on, the GPUs used (0 on the CPU) and the
  /// sizes of its current structures into `stats`.
  virtual void describe(SolverStats& stats) const = 0;
  /// Before stage MethodSpec::memorySampleStage() runs, the stages before it having run:
  /// measures on a sample of the elements what that stage allocates per element
  /// (MemoryShape::sampledPerElement), allocating little and keeping nothing. Under MPI on
  /// a sample of this process's rows, per element of the whole mesh: what this process
  /// will hold.
  virtual double sampleMemory(const StageContext& /*context*/) { return 0.0; }
  /// After a commit: a ray tracer over the committed scene, for checks of the result
  /// (litOnlyOnTheirBacks): the CPU backends' own, the GPU backends' BVH through copies of
  /// the rays; nullptr where the backend has none.
  virtual const RayTracer* sceneTracer() const { return nullptr; }
};

/// One stage's result in a backend: what the last commit kept, and what this update staged.
/// A stage writes stage(); later stages of the update read now(); commit() keeps the staged
/// value (and frees the one it replaces), discard() drops it.
template <typename T>
class Staged
{
public:
  T& stage()
  {
    staged = true;
    return next;
  }
  const T& now() const { return staged ? next : kept; }
  /// The last commit's value, whatever this update staged (what describe() reports).
  const T& committed() const { return kept; }
  void commit()
  {
    if (staged)
    {
      std::swap(kept, next);
      next = T();
      staged = false;
    }
  }
  void discard() { staged = false; }

private:
  T kept, next;
  bool staged = false;
};

/// A solution method: its stages, and its backends.
class MethodSpec
{
public:
  virtual ~MethodSpec() = default;
  virtual const char* name() const = 0; ///< "links"
  virtual const std::vector<StageSpec>& stages() const = 0;
  /// Checks the method's own options (its field of SolverOptions) against their limits;
  /// throws Error naming the option. validateOptions() asks every registered method, so a
  /// bad value is refused whichever method is chosen.
  virtual void validateOptions(const SolverOptions& /*options*/) const {}
  /// Refuses, with an Error that says what to change, shared options the method cannot take
  /// (implicit visibility: two-sided elements). Asked only when the method is the chosen one.
  virtual void checkCombination(const SolverOptions& /*options*/) const {}
  /// Whether the method's own options differ between `a` and `b`: for SolverOptions'
  /// equality and the change bit kMethodOptions.
  virtual bool optionsDiffer(const SolverOptions& /*a*/, const SolverOptions& /*b*/) const { return false; }
  /// The sampling `options` ask of it, in its own words ("256 rays"): what a progressive
  /// stage or a benchmark reports.
  virtual std::string sampling(const SolverOptions& /*options*/) const { return {}; }
  /// Whether it carries light through mirror and glass triangles (else they are diffuse,
  /// and the orchestrator says so).
  virtual bool carriesSpecular() const { return false; }
  /// The CPU implementation; always exists.
  virtual std::unique_ptr<MethodBackend> createCpu(const SolverOptions& options) const = 0;
  /// The CUDA implementation on up to options.cudaDevices GPUs. Throws CudaError when no
  /// device can be used. A method overrides it where its CUDA backend is built (its
  /// Method.cmake's CUDA_SOURCES, LINKGI_HAVE_CUDA); this one says there is none.
  virtual std::unique_ptr<MethodBackend> createCuda(const SolverOptions& options) const;
  /// Whether createCuda makes a backend in this build (overridden with it); a method without
  /// one runs on the CPU under Backend::Auto without a warning (engine/CudaFactory.h asks).
  virtual bool hasCudaBackend() const { return false; }
  /// Peak bytes that running the stages `stale` (bit i: stages()[i]) allocate on a mesh of
  /// `shape`, on the host and on the GPU(s), from the sizes and what the backend sampled
  /// (shape.sampledPerElement) alone. An upper bound where nothing was sampled, rather than
  /// a guess: the orchestrator refuses an update whose host estimate is over the memory
  /// budget (engine/MemoryBudget.h). 0 = nothing to declare.
  virtual MemoryEstimate estimateMemory(const MemoryShape& /*shape*/,
    const SolverOptions& /*options*/, std::uint32_t /*stale*/, bool /*cuda*/) const
  {
    return {};
  }
  /// The stage whose memory the method's CPU backend measures on a sample of the elements
  /// before it runs (MethodBackend::sampleMemory), because its sizes alone bound it only
  /// loosely; -1: none. The orchestrator then checks the budget twice: before the update for
  /// the stages before that one, and before that one for all, with what was sampled.
  virtual int memorySampleStage() const { return -1; }
  /// Progressive updates (AsyncSolver): the work of the sampling that `options` asks for on
  /// `elements` elements, in the method's own unit (rays traced, vertex-VPL pairs): what
  /// coarser() scales and what time is predicted from. 0: the method has no coarser solution.
  virtual double sampleWork(std::size_t /*elements*/, const SolverOptions& /*options*/) const
  {
    return 0.0;
  }
  /// The options of a coarser solution of the same light whose sampling work is about
  /// `fraction` (in (0, 1)) of that of `options`: fewer rays, VPLs, photons or bins, never
  /// below the method's smallest useful sampling; every other option unchanged.
  virtual SolverOptions coarser(const SolverOptions& options, double /*fraction*/) const
  {
    return options;
  }
};

/// Under MPI (SolverOptions::partition): this process's rows, one flag per element, or null
/// (every row); throws Error when the mask does not fit `elements` or has no exchange. A
/// method that splits its work by rows computes only these and completes the rest with the
/// partition's exchange.
const std::uint8_t* ownRows(const SolverOptions& options, std::size_t elements);

/// How many rows of `elements` are this process's (all without a partition).
std::size_t ownRowCount(const SolverOptions& options, std::size_t elements);

/// The partition's exchange (Partition::exchange) as the bounce loops take it; empty without
/// a partition.
std::function<void(std::vector<Vec3f>&)> exchangeOf(const SolverOptions& options);

/// The registry: the one place that names every method (Methods.cpp).
const MethodSpec& methodSpec(Method method);
}
