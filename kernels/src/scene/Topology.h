// One-ring adjacency of a triangle mesh in compressed sparse row form.
#pragma once

#include "linkgi/Scene.h"

#include <vector>

namespace linkgi
{
/// For each vertex: its neighbour vertices (sharing an edge) and its unique edges.
struct Topology
{
  std::vector<Index> neighbourOffsets; ///< size vertexCount + 1
  std::vector<Index> neighbours;       ///< sorted, unique per vertex
  /// Unique undirected edges (a < b); edge midpoints are the 1:4 subdivision points.
  std::vector<std::pair<Index, Index>> edges;
  /// For each vertex the indices into `edges` of its incident edges (CSR, same offsets as
  /// neighbours, in the same order).
  std::vector<Index> vertexEdges;

  static Topology build(std::size_t vertexCount, const std::vector<Triangle>& triangles);
  std::size_t vertexCount() const { return neighbourOffsets.empty() ? 0 : neighbourOffsets.size() - 1; }
};

/// Vertex -> incident triangles, in CSR form: vertex v's triangles (indices into
/// `triangles`, ascending) are incident[offsets[v]] to incident[offsets[v + 1] - 1].
void incidentTriangles(std::size_t vertexCount, const std::vector<Triangle>& triangles,
  std::vector<Index>& offsets, std::vector<Index>& incident);
}
