// Which surfaces of a solved one-sided scene its lights reach only on their backs, with
// shadow rays through the scene's tracer: a check of a result, below the public API
// (linkgi/Orientation.h holds those that need none, and surfaceLabels).
#pragma once

#include "linkgi/Orientation.h"
#include "shared/RayTracer.h"

#include <cstdint>
#include <vector>

namespace linkgi
{
/// The surfaces of a one-sided scene that its lights reach only on their backs while others
/// are lit in front: none of their vertices has direct light (`direct`), and of the shadow
/// rays from the backs of the centres of up to kBackRays of their triangles that face away
/// from a light, at least half reach it. Polygons of mixed orientation (GIS data), sheets turned away from
/// the lights. A closed object's far side is not one (its back looks into the object), nor a
/// lamp shade's outside behind its inside. At most kBackSamples rays in all. `surfaceOf`:
/// surfaceLabels' of the scene; `tracer`: over the scene.
struct LitOnTheirBacks
{
  std::size_t surfaces = 0;  ///< lit only on their backs
  std::size_t triangles = 0; ///< theirs
  std::size_t frontLit = 0;  ///< surfaces with direct light on their fronts
  /// Triangles of the surfaces whose side is known: all but those past kBackSamples rays.
  std::size_t knownTriangles = 0;
};
LitOnTheirBacks litOnlyOnTheirBacks(const Scene& scene, const std::vector<Index>& surfaceOf, std::size_t surfaces,
  const std::vector<Vec3f>& direct, const RayTracer& tracer);
constexpr int kBackRays = 8;
constexpr std::size_t kBackSamples = 65536;
}
