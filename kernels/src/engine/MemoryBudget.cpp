#include "engine/MemoryBudget.h"

#include "linkgi/Error.h"
#include "shared/Sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace linkgi::engine
{
MemoryVerdict judgeMemory(const MethodSpec& spec, const MemoryShape& shape,
  const SolverOptions& options, std::uint32_t stale, bool cuda, std::uint64_t budget)
{
  MemoryVerdict v;
  v.budget = budget;
  v.estimate = spec.estimateMemory(shape, options, stale, cuda);
  v.fits = v.estimate.hostBytes <= budget;
  if (v.fits)
  {
    return v;
  }
  // Fewer rays: the largest perfect square below the request whose estimate fits.
  SolverOptions fewer = options;
  for (std::uint32_t k = squareSide(options.raysPerVertex); k-- > 1;)
  {
    fewer.raysPerVertex = k * k;
    const std::uint64_t bytes = spec.estimateMemory(shape, fewer, stale, cuda).hostBytes;
    if (bytes == v.estimate.hostBytes)
    {
      break; // the method's memory does not depend on the rays
    }
    if (bytes <= budget)
    {
      v.raysThatFit = k * k;
      break;
    }
  }
  // A smaller mesh: the estimate grows with the vertex count, so bisect on the fraction of
  // this mesh's vertices and triangles that fits, with what this mesh sampled (a proxy's
  // own update is judged again with its own sample).
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    MemoryShape smaller = shape;
    smaller.vertices = std::uint64_t(double(shape.vertices) * mid);
    smaller.triangles = std::uint64_t(double(shape.triangles) * mid);
    (spec.estimateMemory(smaller, options, stale, cuda).hostBytes <= budget ? lo : hi) = mid;
  }
  v.verticesThatFit = std::uint64_t(double(shape.vertices) * lo);
  return v;
}

std::uint64_t memoryLeft(const SolverStats& stats, std::uint64_t held)
{
  if (stats.memoryBudget == 0)
  {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return stats.memoryBudget > held ? stats.memoryBudget - held : 0;
}

void raiseEstimate(SolverStats& stats, std::uint64_t bytes)
{
  stats.hostBytesEstimated = std::max(stats.hostBytesEstimated, bytes);
}

void checkMemoryBudget(const MethodSpec& spec, const MemoryShape& shape, const SolverOptions& options,
  std::uint32_t stale, bool cuda, SolverStats& stats, std::uint32_t first)
{
  const std::uint64_t budget = hostMemoryBudget(options.memoryBudget);
  MemoryVerdict v = judgeMemory(spec, shape, options, stale & first, cuda, budget);
  if (!v.fits && (stale & first) != stale)
  {
    // The whole update needs more than its first stages: what would fit is what fits all.
    v = judgeMemory(spec, shape, options, stale, cuda, budget);
  }
  stats.hostBytesEstimated = v.estimate.hostBytes;
  stats.memorySampledPerElement = shape.sampledPerElement;
  stats.deviceBytesEstimated = v.estimate.deviceBytes;
  stats.memoryBudget = v.budget;
  // Under MPI each process judges its own part (its rows, its sample) under its own budget,
  // and all agree in one allreduce: every process runs the update, or every one refuses it
  // with the smallest mesh that fits them all.
  constexpr std::uint64_t kFits = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t fitAll =
    options.partition ? options.partition->smallest(v.fits ? kFits : v.verticesThatFit) : kFits;
  if (v.fits && fitAll == kFits)
  {
    return;
  }
  const std::uint64_t fit = std::min(v.fits ? kFits : v.verticesThatFit, fitAll);
  const std::string rays = std::to_string(options.raysPerVertex);
  const std::string fits = fit > 0 ?
    " a mesh of at most " + std::to_string(fit) + " vertices at " + rays +
      " rays per vertex (decimate the input, or light it through a proxy of that size: ProxyVertices);" :
    " no mesh at " + rays + " rays per vertex;";
  if (v.fits)
  {
    throw OutOfMemoryBudget("Not enough memory on another process that shares the surface: its part of this "
                            "update of the " + std::string(spec.name()) +
        " method is over its memory budget. What would fit every process:" + fits +
        " or larger memory budgets, if the machines have the memory.",
      fit);
  }
  std::string message = "Not enough memory: this update of the " + std::string(spec.name()) +
    " method would need about " + formatBytes(v.estimate.hostBytes) + " of host memory (" +
    std::to_string(shape.vertices) + " vertices" + (options.partition ? ", this process's rows of them, " : ", ") +
    rays + " rays per vertex), over the memory budget of " + formatBytes(budget) +
    (options.memoryBudget ? " (MemoryBudget)" :
                            " (what the machine has available, " + formatBytes(availableHostBytes()) + ", less a margin)") +
    ". What would fit" + (options.partition ? " every process" : "") + ":";
  if (v.raysThatFit > 0 && !options.partition)
  {
    message += " " + std::to_string(v.raysThatFit) + " rays per vertex on this mesh;";
  }
  message += fits + " or a larger MemoryBudget, if the machine has the memory.";
  throw OutOfMemoryBudget(message, fit);
}
}
