// Scenes of linkgi-bench beyond the standard ones.
#pragma once

#include "linkgi/Scene.h"

#include <string>

namespace linkgi::bench
{
/// A standard scene (see Scenes.h), or "isosurface": the zero level set of
/// f(x) = |x - c| - R(direction) (a bumpy closed blob, star-shaped around c) tessellated in
/// spherical coordinates with about 1.05M vertices, standing in a tiled room under two point
/// lights: the scale test of a fine scientific isosurface. "isosurface:N" tessellates the
/// same blob with about N vertices.
Scene makeScene(const std::string& name);
}
