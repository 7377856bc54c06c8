// linkgi-bench's --dump / --compare: solutions stored as files and compared across builds
// and backends.
#pragma once

#include "linkgi/Scene.h"
#include "linkgi/SolverTypes.h"

#include <string>

namespace linkgi::bench
{
/// Writes the element count and the three outputs (raw floats); throws Error on failure.
void writeSolution(const std::string& path, const Solution& s);
/// Reads what writeSolution wrote; throws Error on failure.
Solution readSolution(const std::string& path);
/// Worst channel of the relative RMSE of each output against `reference`, area-weighted
/// ("aw") and per vertex unweighted ("pv"), as a JSON object.
std::string agreement(const Scene& scene, const Solution& a, const Solution& reference);
}
