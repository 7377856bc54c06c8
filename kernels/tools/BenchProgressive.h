// linkgi-bench --progressive: what a progressive background update publishes, stage by stage.
#pragma once

#include "linkgi/Scene.h"
#include "linkgi/SolverTypes.h"

#include <string>

namespace linkgi::bench
{
/// One JSON object: for a first update ("apply"), deformation steps and light moves of
/// `scene`, `repeat` times each, every stage an AsyncSolver with progressive updates
/// published - its sampling, when it arrived after the request, and its area-weighted
/// relative RMSE (luminance) against the update's final solution - and the same update's
/// time without progressive stages.
std::string progressiveJson(const std::string& name, const Scene& scene, const SolverOptions& options, int repeat);
}
