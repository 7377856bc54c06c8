// The solver: one orchestrator over every method and backend, with caching by what changed
// (Documentation/Engine.md).
#pragma once

#include "linkgi/SolverTypes.h"

#include <memory>
#include <string>
#include <vector>

namespace linkgi
{
/// Computes direct and multi-bounce indirect irradiance per vertex. Between updates it keeps
/// the acceleration structure, the link matrix and the direct light, and recomputes only
/// what the new scene and options invalidate:
///   lights only -> light links + bounces;   albedo/emission/environment -> bounces;
///   positions or normals -> refit + links + everything after;   triangles -> everything.
class Solver
{
public:
  Solver();
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  /// Solves `scene`. Throws linkgi::Error for invalid input and linkgi::Aborted when
  /// `progress` returns false; in both cases solution() still returns the previous result.
  const Solution& update(const Scene& scene, const SolverOptions& options = {},
    const ProgressCallback& progress = {});

  const Solution& solution() const;
  const SolverStats& stats() const;
  /// Forgets every cached stage; the next update recomputes everything.
  void reset();

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
}
