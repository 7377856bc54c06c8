// Procedural meshes appended to a Scene, with per-vertex normal, albedo and emission.
#pragma once

#include "linkgi/Scene.h"

#include <functional>
#include <utility>

namespace linkgi
{
/// How a parametric (u, v) grid closes on itself (see MeshBuilder::addSurface).
struct SurfaceTopology
{
  bool wrapU = false;  ///< u = 0 and u = 1 are the same curve (tubes, revolutions)
  bool wrapV = false;  ///< v = 0 and v = 1 are the same curve (torus)
  bool poleAtV0 = false; ///< the whole curve v = 0 is one point (sphere pole, disk centre)
  bool poleAtV1 = false; ///< the whole curve v = 1 is one point (sphere pole, cone tip)

  static SurfaceTopology sheet() { return {}; }
  static SurfaceTopology tube() { return { true, false, false, false }; }
  static SurfaceTopology closed() { return { true, false, true, true }; }
  static SurfaceTopology torus() { return { true, true, false, false }; }
};

/// Appends shapes to a Scene. The solver's elements are vertices, so:
/// - flat faces (quads, boxes, disks, caps) get vertices of their own, never shared with a
///   neighbouring face of another orientation (a sharp edge splits its vertices);
/// - smooth shapes (spheres, tube sides, tori, parametric surfaces) share vertices and carry
///   smooth normals.
/// Triangles wind counter-clockwise seen from the side the normals point to. Every add*()
/// returns the index of its first vertex, so that a shape can be moved or deformed later
/// (rotateY, deform), and all sizes are in scene units.
class MeshBuilder
{
public:
  MeshBuilder() = default;
  /// Continues an existing scene; its vertices, lights and environment are kept.
  explicit MeshBuilder(Scene scene) : target(std::move(scene)) {}

  Scene& scene() { return target; }
  /// Hands the scene over; the builder is empty afterwards.
  Scene take();
  Index vertexCount() const { return static_cast<Index>(target.positions.size()); }

  Index addVertex(const Vec3f& position, const Vec3f& normal, const Vec3f& albedo,
    const Vec3f& emission = {});
  void addTriangle(Index a, Index b, Index c);

  /// Parallelogram origin + s*edgeU + t*edgeV, s,t in [0,1], split into nu x nv cells.
  /// Normal = normalize(cross(edgeU, edgeV)).
  Index addQuadGrid(const Vec3f& origin, const Vec3f& edgeU, const Vec3f& edgeV, int nu, int nv,
    const Vec3f& albedo, const Vec3f& emission = {});
  /// Planar quad p0 p1 p2 p3 (counter-clockwise seen from its lit side), bilinearly split
  /// into nu cells along p0->p1 and nv cells along p0->p3. Normal from the diagonals.
  Index addQuad(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Vec3f& p3, int nu,
    int nv, const Vec3f& albedo, const Vec3f& emission = {});
  /// Axis-aligned box: six faces with their own vertices, cells at most `cellSize` wide.
  /// `inward` turns the faces towards the inside (rooms).
  Index addBox(const Vec3f& min, const Vec3f& max, float cellSize, const Vec3f& albedo,
    bool inward = false, const Vec3f& emission = {});
  /// Flat disk facing `normal`, `segments` around and `rings` from centre to rim.
  Index addDisk(const Vec3f& center, const Vec3f& normal, float radius, int segments, int rings,
    const Vec3f& albedo, const Vec3f& emission = {});
  /// UV sphere: `rings` bands from pole to pole (>= 2), `segments` around the Y axis.
  Index addSphere(const Vec3f& center, float radius, int rings, int segments,
    const Vec3f& albedo, const Vec3f& emission = {}, bool inward = false);
  /// Icosphere: 10 * 4^level + 2 vertices of almost equal area; exact radial normals.
  Index addIcosphere(const Vec3f& center, float radius, int level, const Vec3f& albedo,
    const Vec3f& emission = {}, bool inward = false);
  /// Truncated cone from `base` (radius baseRadius) to `top` (radius topRadius; 0 = a tip).
  /// `caps` adds flat disks at the ends whose radius is not zero.
  Index addCone(const Vec3f& base, const Vec3f& top, float baseRadius, float topRadius,
    int segments, int stacks, bool caps, const Vec3f& albedo, const Vec3f& emission = {},
    bool inward = false);
  Index addCylinder(const Vec3f& base, const Vec3f& top, float radius, int segments, int stacks,
    bool caps, const Vec3f& albedo, const Vec3f& emission = {}, bool inward = false)
  {
    return addCone(base, top, radius, radius, segments, stacks, caps, albedo, emission, inward);
  }
  /// Torus around `axis` through `center`: `majorSegments` around the axis, `minorSegments`
  /// around the tube.
  Index addTorus(const Vec3f& center, const Vec3f& axis, float majorRadius, float minorRadius,
    int majorSegments, int minorSegments, const Vec3f& albedo, const Vec3f& emission = {});
  /// Surface of revolution around the line base + t*axis (axis unit length) of the profile
  /// (radius, height) points; a first or last point with radius 0 closes that end with a
  /// single pole vertex. Profile going up with height faces away from the axis.
  Index addRevolution(const Vec3f& base, const Vec3f& axis,
    const std::vector<std::pair<float, float>>& profile, int segments, const Vec3f& albedo,
    const Vec3f& emission = {}, bool inward = false);
  /// General smooth surface: point(u, v) for u, v in [0, 1], nu x nv cells, closed as
  /// `topology` says. Normals are area-weighted averages of the adjacent triangles and face
  /// the side of cross(dP/du, dP/dv) (the other side when `inward`).
  Index addSurface(const std::function<Vec3f(float u, float v)>& point, int nu, int nv,
    SurfaceTopology topology, const Vec3f& albedo, const Vec3f& emission = {},
    bool inward = false);

  /// Rotates vertices [firstVertex, end) by `radians` about the vertical line through `pivot`
  /// (counter-clockwise seen from +Y).
  void rotateY(Index firstVertex, const Vec3f& pivot, float radians);
  /// Moves vertices [firstVertex, end) through a smooth, orientation-preserving map; the
  /// normals follow through the map's Jacobian (cofactor matrix, by central differences), so
  /// topology, winding and smoothness are kept.
  void deform(Index firstVertex, const std::function<Vec3f(const Vec3f&)>& map);

private:
  /// Grid of (u, v) samples closed per `topology`; returns the first vertex.
  Index addGrid(const std::function<Vec3f(float, float)>& point, int nu, int nv,
    SurfaceTopology topology, const Vec3f& albedo, const Vec3f& emission, bool inward);
  /// Smooth normals of vertices [firstVertex, end) from triangles [firstTriangle, end).
  void smoothNormals(Index firstVertex, std::size_t firstTriangle);

  Scene target;
};
}
