// Which side of a surface is its front, checked before lighting: real data is often wound
// inward (scanned models saved with clockwise triangles) or lit from behind.
#pragma once

#include "linkgi/Scene.h"

#include <cstdint>
#include <vector>

namespace linkgi
{
/// A closed surface whose normals point inward: an object wound inside out, or a room.
struct InwardSurface
{
  std::vector<Index> vertices;
  std::vector<Index> triangles;
  Vec3f lo, hi; ///< its bounds: a light outside them is outside it, with no sum to take
};

/// The connected surfaces of a scene and those among them that are closed and face inward.
struct SurfaceOrientation
{
  std::size_t surfaces = 0; ///< connected through shared points
  std::vector<InwardSurface> inward;
  /// Triangles whose winding disagrees with their vertices' normals (the engine follows the
  /// normals; VTK's two-sided lighting follows the winding and draws them dark).
  std::size_t againstWinding = 0;
  /// Vertices whose normal lies more than kBentNormalDegrees from the front of every one of
  /// their triangles, and their share of the surface's area (a third of each triangle per
  /// corner): normals averaged across sharp edges, as CAD exports write them, which tilt the
  /// hemisphere such a vertex is lit over away from all its faces.
  std::size_t bentNormals = 0;
  double bentNormalArea = 0.0;
};

/// How far a vertex normal may lie from the nearest of its triangles before it counts as
/// bent (SurfaceOrientation::bentNormals): a normal averaged over two faces at a right angle
/// lies 45 degrees from both, over a cube's three 55 degrees; a contour's gradient normals
/// lie near one of their facets (PyVista's carotid at its mid value: 3% of the area beyond
/// 30 degrees, though 37% lies more than 45 degrees from some facet), scanned models' own
/// normals too (the bunny, a cow: 0-3%).
constexpr double kBentNormalDegrees = 30.0;

/// Finds the closed surfaces whose normals point inward. A surface is a set of triangles
/// connected through shared points: `pointIds` gives each vertex the id of the point it was
/// split from at sharp edges (empty: every vertex is its own point), and points at the same
/// position are one (a seam where a surface repeats its points).
/// A surface counts as closed when its holes are small: the squared length of their
/// borders is at most 3x its area (the Stanford bunny's five holes: 2.0; an open bowl 6.3,
/// a tube open at both ends 12.6, a square 16). It faces inward when its volume, integrated
/// over the sides its normals point to, is negative and decisive: above 2x its bounding
/// radius times its vector area (what the holes leave open, zero when closed) and above
/// 1e-3 of its area times that radius. Open surfaces (planes, bowls, tunnels, terrain) have
/// no inside and are never listed. Positions are taken relative to each surface's centre,
/// so a translation changes no decision.
SurfaceOrientation findInwardSurfaces(const Scene& scene, const std::vector<std::uint64_t>& pointIds);

/// Whether a light of the scene is inside `surface`: a point or spot light, or an emitting
/// vertex of another surface, where the surface's winding number is at least 1/2. A room
/// lit from within faces inward by design; an object wound inside out has its lights outside.
/// A light outside the surface's bounds costs nothing; one inside them a pass over its
/// triangles.
bool hasLightInside(const Scene& scene, const InwardSurface& surface);

/// Negates the normals of `surface`'s vertices (the engine's front is where they point).
void flipNormals(Scene& scene, const InwardSurface& surface);

/// Whether the scene's lights reach only the back of a one-sided scene: no vertex receives
/// light on the side its normal points to, and some vertex would on the other side (a
/// surface whose normals face away from every light). Visibility is not traced.
bool litOnlyFromBehind(const Scene& scene);

/// How much of the light of the scene's lights that faces its front sides reaches them:
/// the direct irradiance `direct` (shadows and all) over what the lights would give the same
/// vertices unshadowed, summed in luminance over every k-th vertex (at most kLitShareSamples
/// vertex-light pairs). Near 0 where the fronts that face the lights lie in the shadow of
/// the rest: a surface wound inside out, open or not (its fronts face its inside, behind
/// its near side), or lights shut away from what they face. 1 where no front faces a light.
/// Emission and the environment are not counted: the caller asks only without them.
float litShareOfFronts(const Scene& scene, const std::vector<Vec3f>& direct);
constexpr std::size_t kLitShareSamples = 65536;

/// Per vertex, its surface: vertices joined by triangles, numbered from 0 (vertices split
/// from one point at sharp edges part a closed object into several); `count` gets how many.
std::vector<Index> surfaceLabels(const Scene& scene, std::size_t& count);
}
