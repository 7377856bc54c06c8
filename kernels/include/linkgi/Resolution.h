// The resolution a surface is lit at: as given, through a decimated proxy (the indirect light
// solved on a coarser copy and carried back to every vertex, for a surface too fine for the
// memory or the time), or refined where the light asks for it (Documentation/Methods.md,
// "Proxies" and "Refinement"). ResolvedSolver takes the choice as an option of one solve;
// AsyncSolver takes the same options in the background.
#pragma once

#include "linkgi/Scene.h"
#include "linkgi/Solver.h"
#include "linkgi/SolverTypes.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkgi
{
/// True if this build has OpenMesh (without it, decimate() throws Error saying so).
bool proxyAvailable();

/// A decimated copy of a scene.
struct ProxyMesh
{
  Scene scene; ///< positions, normals, albedo, emission of the kept vertices; lights, environment
  std::vector<Index> sourceVertex; ///< for each proxy vertex, the input vertex it is
  std::size_t droppedTriangles = 0; ///< input triangles OpenMesh could not take (non-manifold)
};

/// Lighting through a proxy: the indirect light is solved on a decimated copy of the mesh
/// (any method, any backend, under the memory budget: an ordinary Solver) and carried to
/// every input vertex; the direct light of the point, spot and directional lights is
/// computed on the input itself (shadow rays per input vertex, the light-link code of the
/// CPU). The proxy, its transfer and the input's shadow-ray structures are kept while the
/// input's geometry and the target stay the same: a light move does not decimate again.
class ProxySolver
{
public:
  ProxySolver();
  ~ProxySolver();
  ProxySolver(const ProxySolver&) = delete;
  ProxySolver& operator=(const ProxySolver&) = delete;

  /// Solves `scene` with a proxy of about `proxyVertices` vertices (Error when that is 0 or
  /// not smaller than the input). Same errors and guarantees as Solver::update: after an
  /// error or abort, solution() is the previous result.
  const Solution& update(const Scene& scene, const SolverOptions& options, std::size_t proxyVertices,
    const ProgressCallback& progress = {});
  const Solution& solution() const;
  /// The proxy solve's statistics (its elements are the proxy's), plus "Decimate",
  /// "Transfer" and "InputDirect" parts when they ran.
  const SolverStats& stats() const;
  /// The current proxy, and how many times one was made.
  const ProxyMesh& proxy() const;
  std::uint64_t decimations() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

struct RefinementOptions
{
  /// An edge is split when, relative to the local level of light (the mean total irradiance
  /// of its two ends, at least 2% of the scene's mean): its ends' direct or indirect
  /// irradiance differ by more than this, or the exact direct light at its midpoint differs
  /// from the mean of its ends' by more than this (a shadow boundary or a light's peak
  /// between the two vertices). In (0, 10]. Default 0.1.
  float tolerance = 0.1f;
  /// The refined mesh stops growing at this many vertices; when a round has more edges to
  /// split than that leaves, the worst ones are split. 0 (default): 4 times the input's.
  std::size_t maxVertices = 0;
  /// Rounds of splitting, each followed by a solve of the refined mesh. 1 to 10. Default 3.
  std::uint32_t rounds = 3;
};

/// A refined copy of a scene. Vertices [0, inputVertices) are the input's, unchanged; every
/// later vertex v is the midpoint of the two lower-numbered vertices midpointOf[v -
/// inputVertices] (position, albedo and emission their mean, normal their normalized sum),
/// so any per-vertex quantity of the input is carried over exactly by interpolating in
/// vertex order. Every triangle lies inside one input triangle: edges are only ever split at
/// their midpoints, so the input's edges (boundaries and sharp creases among them) and its
/// surface stay exactly where they were.
struct RefinedScene
{
  Scene scene;
  std::size_t inputVertices = 0;
  std::vector<std::array<Index, 2>> midpointOf;
  /// Per triangle: the input triangle it lies in (an index into the input's triangles as
  /// given, before validation removed degenerate ones).
  std::vector<Index> sourceTriangle;
};

/// Solving with refinement: solve the input, then up to `rounds` times split the edges
/// edgesToRefine names (within the vertex budget) and solve the refined mesh. Each solve is
/// a full update of an ordinary Solver (a new mesh is a topology change).
class RefiningSolver
{
public:
  RefiningSolver();
  ~RefiningSolver();
  RefiningSolver(const RefiningSolver&) = delete;
  RefiningSolver& operator=(const RefiningSolver&) = delete;

  /// Solves `scene` with refinement. Errors as Solver::update, plus bad refinement options;
  /// after an error or an abort, refined() and solution() are those of the previous update.
  /// The surface is refined when the input's geometry, materials or the options changed
  /// since the last update; a change of lights, albedo, emission or environment alone keeps
  /// it (refined for the light it had then) and solves only its light, as fast as without
  /// refinement.
  const Solution& update(const Scene& scene, const SolverOptions& options,
    const RefinementOptions& refinement, const ProgressCallback& progress = {});
  /// The refined mesh of the last update, and its light (elements = its vertices).
  const RefinedScene& refined() const;
  const Solution& solution() const;
  /// The last round's solve, with the parts "Refine" (finding and splitting edges) and the
  /// whole update's time in msTotal; warnings from validation, deduplicated.
  const SolverStats& stats() const;
  /// Rounds that split edges in the last update (0: the input was fine enough), and the
  /// edges each split.
  const std::vector<std::uint64_t>& splitsPerRound() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};

/// The resolution of one solve.
struct ResolutionOptions
{
  /// 0 (default): the surface as given, or, where the memory budget refuses it, through a
  /// proxy of half the vertices that would fit (chosen when the surface or the options
  /// change, kept over light moves; not below 1000 vertices, where the budget's error stands).
  /// N > 0: through a proxy of about N vertices (fewer than the surface has).
  std::size_t proxyVertices = 0;
  /// Refined where the light asks for it (the result is a new surface: ResolvedSolver::
  /// refined()); excludes a proxy, partitions and background updates.
  bool refine = false;
  RefinementOptions refinement;
};
bool operator==(const ResolutionOptions& a, const ResolutionOptions& b);
inline bool operator!=(const ResolutionOptions& a, const ResolutionOptions& b)
{
  return !(a == b);
}

/// The one check of what does not combine: refinement with a proxy, with a partition (a
/// refined global surface has points no process owns), or in the background (its result is
/// a new surface); throws Error saying what to change. `background`: an AsyncSolver asks.
void checkResolution(const SolverOptions& options, const ResolutionOptions& resolution, bool background);

/// One solve at the resolution asked: an ordinary Solver for the surface as given, a
/// ProxySolver, or a RefiningSolver, each kept between updates (a light move through a
/// proxy does not decimate again). Same errors and guarantees as Solver::update.
class ResolvedSolver
{
public:
  ResolvedSolver();
  ~ResolvedSolver();
  ResolvedSolver(const ResolvedSolver&) = delete;
  ResolvedSolver& operator=(const ResolvedSolver&) = delete;

  const Solution& update(const Scene& scene, const SolverOptions& options,
    const ResolutionOptions& resolution = {}, const ProgressCallback& progress = {});
  /// A coarser solution of the surface as given, for a progressive update: solved by the
  /// solver the next update() with the final options uses, so that the stages the sampling
  /// does not touch (the surface's structures, the direct light) run once for both. Never
  /// through a proxy: throws OutOfMemoryBudget where the surface is over the budget.
  const Solution& updateCoarse(
    const Scene& scene, const SolverOptions& coarse, const ProgressCallback& progress = {});
  /// The last update's solution: per element of the surface (the refined one when refined).
  const Solution& solution() const;
  /// The last update's statistics, with a warning when the memory budget chose a proxy.
  const SolverStats& stats() const;
  /// The refined surface when the last update refined, else null.
  const RefinedScene* refined() const;
  /// The proxy's vertex count when the last update went through one, else 0.
  std::size_t proxyVertices() const;
  /// Forgets every cached stage and the budget's proxy.
  void reset();

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
}
