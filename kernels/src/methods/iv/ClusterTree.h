// The element hierarchy of the implicit-visibility method (Dong, Kautz, Theobalt & Seidel
// 2007): discs at the vertices clustered into a binary position+normal tree. The structure
// is built when the topology changes; positions, normals, areas and bounds are refit on
// every update. See Documentation/Methods.md, "Implicit visibility".
#pragma once

#include "linkgi/Scene.h"

#include <vector>

namespace linkgi::iv
{
/// Nodes 0..leafCount-1 are the leaves (node v = the disc of vertex v); interior nodes
/// follow, each after its two children (increasing index = bottom-up), the root last.
struct ClusterTree
{
  std::size_t leafCount = 0;
  std::vector<Index> left, right; ///< children of interior node leafCount + i
  std::vector<Index> parent;      ///< per node; kInvalidIndex for the root

  // Per node, from refit():
  std::vector<Vec3f> position; ///< area-weighted mean of the children's (leaf: the vertex)
  std::vector<Vec3f> normal;   ///< unit, area-weighted mean direction (leaf: the vertex's)
  std::vector<float> area;     ///< disc area: a third of the adjacent triangles, summed
  /// Bounding sphere about `position` of every disc below (a leaf: its disc, sqrt(area/pi)).
  std::vector<float> radius;
  /// Half angle (radians) of a cone about `normal` holding every leaf normal below.
  std::vector<float> coneAngle;
  /// Bound on |normal . (p - position)| over every disc point p below: the slab the
  /// cluster lies in (0 for a leaf and, up to rounding, for a flat patch).
  std::vector<float> planeDeviation;
  /// Per leaf: how far its element reaches from its vertex (the farthest corner of its part
  /// of each adjacent triangle: an edge's midpoint or the centroid), at least its disc's
  /// radius. A long thin triangle's element reaches far beyond its disc.
  std::vector<float> extent;
  /// Per leaf: bound on |normal . (q - vertex)| over those corners q: the slab its element
  /// lies in (0 on a flat patch).
  std::vector<float> extentSlab;

  std::size_t nodeCount() const { return position.size(); }
  Index root() const { return Index(nodeCount() - 1); }
  bool isLeaf(Index node) const { return node < leafCount; }

  /// Builds the structure from the scene's current positions and normals and refits it.
  /// `areas`: per vertex (linkgi::vertexAreas).
  static ClusterTree build(const Scene& scene, const std::vector<float>& areas);

  /// New node data for moved vertices (same vertex count; the structure is kept): every
  /// value is a function of the structure and the leaves alone, so refitting to a pose
  /// gives what building on it with the same structure gives, bit for bit.
  void refit(const Scene& scene, const std::vector<float>& areas);
};
}
