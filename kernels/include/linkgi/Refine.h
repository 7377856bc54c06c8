// Adaptive refinement: the lighting's resolution follows the light, not the input's
// tessellation. Solve, split the edges across which the light changes too much or along which
// a shadow boundary runs, solve again, for a few rounds. Any method and backend solves each
// round (an ordinary Solver); see Documentation/Methods.md, "Refinement".
#pragma once

#include "linkgi/Solver.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkgi
{
class RayTracer;

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

/// Throws linkgi::Error naming the bad setting (tolerance not in (0, 10] or not finite,
/// rounds not in 1..10, a vertex budget below the input's `inputVertices`).
void validateRefinementOptions(const RefinementOptions& options, std::size_t inputVertices);

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

/// Splits the edges `edges` (pairs of vertex indices, each an edge of some triangle) at their
/// midpoints: a triangle with one split edge becomes 2 triangles, with two 3 (the quad cut
/// along its shorter diagonal), with three 4. Winding is kept. Edges are undirected.
void splitEdges(RefinedScene& refined, const std::vector<std::pair<Index, Index>>& edges);

/// The edges of `scene` that the light `solution` (of that scene) asks to split, worst first:
/// RefinementOptions::tolerance says when. `tracer` is built over the scene (shadow rays of
/// the midpoint test). Edges shorter than 2^-12 of the scene's diagonal are never split.
std::vector<std::pair<Index, Index>> edgesToRefine(const Scene& scene, const Solution& solution,
  const RayTracer& tracer, float tolerance, const ProgressCallback& progress = {});

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
}
