// Refinement's steps (RefiningSolver): its options' check, edge splitting, and which edges
// the light asks to split.
#pragma once

#include "linkgi/Resolution.h"

namespace linkgi
{
class RayTracer;

/// Throws linkgi::Error naming the bad setting (tolerance not in (0, 10] or not finite,
/// rounds not in 1..10, a vertex budget below the input's `inputVertices`).
void validateRefinementOptions(const RefinementOptions& options, std::size_t inputVertices);

/// Splits the edges `edges` (pairs of vertex indices, each an edge of some triangle) at their
/// midpoints: a triangle with one split edge becomes 2 triangles, with two 3 (the quad cut
/// along its shorter diagonal), with three 4. Winding is kept. Edges are undirected.
void splitEdges(RefinedScene& refined, const std::vector<std::pair<Index, Index>>& edges);

/// The edges of `scene` that the light `solution` (of that scene) asks to split, worst first:
/// RefinementOptions::tolerance says when. `tracer` is built over the scene (shadow rays of
/// the midpoint test). Edges shorter than 2^-12 of the scene's diagonal are never split.
std::vector<std::pair<Index, Index>> edgesToRefine(const Scene& scene, const Solution& solution,
  const RayTracer& tracer, float tolerance, const ProgressCallback& progress = {});
}
