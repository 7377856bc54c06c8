// One solve at the resolution asked: the surface as given, through a proxy (chosen by the
// caller or by the memory budget), or refined. What does not combine is refused here alone.
#include "linkgi/Resolution.h"

#include "linkgi/Error.h"
#include "linkgi/Memory.h"

#include <string>

namespace linkgi
{
namespace
{
// Below this, a proxy chosen by the memory budget would light nothing worth seeing: the
// budget's error is reported instead.
constexpr std::size_t kSmallestAutomaticProxy = 1000;
}

bool operator==(const ResolutionOptions& a, const ResolutionOptions& b)
{
  const RefinementOptions &ra = a.refinement, &rb = b.refinement;
  return a.proxyVertices == b.proxyVertices && a.refine == b.refine &&
    ra.tolerance == rb.tolerance && ra.maxVertices == rb.maxVertices && ra.rounds == rb.rounds;
}

void checkResolution(const SolverOptions& options, const ResolutionOptions& resolution, bool background)
{
  if (!resolution.refine)
  {
    return;
  }
  if (resolution.proxyVertices != 0)
  {
    throw Error("Refinement and a proxy exclude each other (one adds points where the light "
                "needs them, the other lights fewer); set one.");
  }
  if (options.partition)
  {
    throw Error("Refinement is not available when the surface is partitioned among processes "
                "(a refined surface has points no process owns); switch it off under MPI.");
  }
  if (background)
  {
    throw Error("Refinement runs in synchronous updates only (its result is a new surface); "
                "switch it off for background updates, or update synchronously.");
  }
}

struct ResolvedSolver::Impl
{
  Solver plain;
  ProxySolver proxy;
  RefiningSolver refining;
  enum class Used
  {
    Plain,
    Proxy,
    Refined
  } used = Used::Plain;
  std::size_t proxyUsed = 0;
  SolverStats stats; // of the solver used, plus this level's warning

  // The proxy the memory budget chose, for a surface of this size at these options (none: 0
  // vertices). It holds until those change: the memory available moves between updates, and
  // a light move must not pick another proxy (and decimate again).
  struct Automatic
  {
    std::size_t vertices = 0, inputVertices = 0, inputTriangles = 0;
    SolverOptions options;
    std::string reason;
  } automatic;
};

ResolvedSolver::ResolvedSolver()
  : impl(new Impl)
{
}

ResolvedSolver::~ResolvedSolver() = default;

const Solution& ResolvedSolver::update(const Scene& scene, const SolverOptions& options,
  const ResolutionOptions& resolution, const ProgressCallback& progress)
{
  checkResolution(options, resolution, false);
  Impl& m = *impl;
  if (resolution.refine)
  {
    m.refining.update(scene, options, resolution.refinement, progress);
    m.used = Impl::Used::Refined;
    m.proxyUsed = 0;
    m.stats = m.refining.stats();
    return m.refining.solution();
  }
  std::size_t target = resolution.proxyVertices;
  std::string note;
  if (target == 0)
  {
    Impl::Automatic& a = m.automatic;
    const bool holds = a.vertices != 0 && a.inputVertices == scene.vertexCount() &&
      a.inputTriangles == scene.triangleCount() && a.options == options;
    if (!holds)
    {
      try
      {
        a = Impl::Automatic();
        m.plain.update(scene, options, progress);
        m.used = Impl::Used::Plain;
        m.proxyUsed = 0;
        m.stats = m.plain.stats();
        return m.plain.solution();
      }
      catch (const OutOfMemoryBudget& tooLarge)
      {
        // Over the budget: a proxy of half what would fit (the proxy itself, the input's
        // shadow-ray structures and the decimation need the rest), if that is still a mesh.
        const std::size_t half = static_cast<std::size_t>(tooLarge.verticesThatFit() / 2);
        if (!proxyAvailable() || half < kSmallestAutomaticProxy)
        {
          throw;
        }
        a = { half, scene.vertexCount(), scene.triangleCount(), options, tooLarge.detail() };
      }
    }
    target = a.vertices;
    note = "The surface is too large for the memory budget, so it is lit through a proxy of "
           "about " + std::to_string(target) + " vertices, chosen when the surface or the "
           "settings last changed (ProxyVertices chooses its size). " + a.reason;
  }
  SolverOptions proxyOptions = options;
  proxyOptions.partition = nullptr; // the proxy's rows are not the surface's: every process solves it
  m.proxy.update(scene, proxyOptions, target, progress);
  m.used = Impl::Used::Proxy;
  m.proxyUsed = m.proxy.proxy().scene.vertexCount();
  m.stats = m.proxy.stats();
  if (!note.empty())
  {
    m.stats.warnings.insert(m.stats.warnings.begin(), note);
  }
  return m.proxy.solution();
}

const Solution& ResolvedSolver::updateCoarse(
  const Scene& scene, const SolverOptions& coarse, const ProgressCallback& progress)
{
  Impl& m = *impl;
  m.plain.update(scene, coarse, progress);
  m.used = Impl::Used::Plain;
  m.proxyUsed = 0;
  m.stats = m.plain.stats();
  return m.plain.solution();
}

const Solution& ResolvedSolver::solution() const
{
  switch (impl->used)
  {
    case Impl::Used::Proxy:
      return impl->proxy.solution();
    case Impl::Used::Refined:
      return impl->refining.solution();
    default:
      return impl->plain.solution();
  }
}

const SolverStats& ResolvedSolver::stats() const
{
  return impl->stats;
}

const RefinedScene* ResolvedSolver::refined() const
{
  return impl->used == Impl::Used::Refined ? &impl->refining.refined() : nullptr;
}

std::size_t ResolvedSolver::proxyVertices() const
{
  return impl->proxyUsed;
}

void ResolvedSolver::reset()
{
  impl.reset(new Impl);
}
}
