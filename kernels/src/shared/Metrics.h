// Accuracy measures of a per-vertex solution against a reference, weighted by surface area
// so that finely tessellated regions do not dominate the error.
#pragma once

#include "linkgi/Scene.h"

#include <vector>

namespace linkgi
{
/// The area each vertex stands for: one third of the area of every triangle it belongs to.
/// Throws linkgi::Error for a triangle index out of range.
std::vector<float> vertexAreas(const Scene& scene);

struct ErrorMetrics
{
  /// Per channel sqrt(sum_i A_i (a_i - r_i)^2 / sum_i A_i r_i^2).
  Vec3f relRmse;
  /// The same on Rec. 709 luminance of a and r.
  float relRmseLuminance = 0.f;
};

/// Area-weighted relative RMSE of `estimate` against `reference`. A channel whose reference
/// is zero everywhere scores 0 if the estimate is zero there too, else +infinity.
/// Throws linkgi::Error if the three arrays differ in size (for two-sided solutions, pass
/// the areas twice, front then back).
ErrorMetrics relativeRmse(const std::vector<Vec3f>& estimate, const std::vector<Vec3f>& reference,
  const std::vector<float>& areas);

/// sum_i A_i v_i / sum_i A_i (0 if the total area is 0). Throws linkgi::Error on a size mismatch.
Vec3f areaWeightedMean(const std::vector<Vec3f>& values, const std::vector<float>& areas);
}
