// Area-weighted error measures. Sums are accumulated in double: meshes have up to ~1e6
// vertices and float sums would lose the digits the comparison is about.
#include "shared/Metrics.h"

#include "linkgi/Error.h"

#include <cmath>
#include <limits>
#include <string>

namespace linkgi
{
namespace
{
void checkSizes(std::size_t values, std::size_t areas, const char* what)
{
  if (values != areas)
    throw Error(std::string(what) + ": " + std::to_string(values) + " values but " +
      std::to_string(areas) + " areas; pass one area per value.");
}

/// sqrt(num / den), with an all-zero reference scoring 0 when matched exactly.
float relativeError(double num, double den)
{
  if (den > 0.0)
    return static_cast<float>(std::sqrt(num / den));
  return num > 0.0 ? std::numeric_limits<float>::infinity() : 0.f;
}
}

std::vector<float> vertexAreas(const Scene& scene)
{
  const std::size_t n = scene.vertexCount();
  std::vector<double> sums(n, 0.0);
  for (const Triangle& t : scene.triangles)
  {
    for (Index v : t.v)
      if (v >= n)
        throw Error("Triangle vertex index " + std::to_string(v) + " is out of range (" +
          std::to_string(n) + " vertices).");
    const Vec3f& a = scene.positions[t.v[0]];
    const double third = length(cross(scene.positions[t.v[1]] - a, scene.positions[t.v[2]] - a)) / 6.0;
    for (Index v : t.v)
      sums[v] += third;
  }
  return std::vector<float>(sums.begin(), sums.end());
}

ErrorMetrics relativeRmse(const std::vector<Vec3f>& estimate, const std::vector<Vec3f>& reference,
  const std::vector<float>& areas)
{
  checkSizes(estimate.size(), reference.size(), "relativeRmse (estimate vs. reference)");
  checkSizes(reference.size(), areas.size(), "relativeRmse");
  double num[4] = { 0, 0, 0, 0 }, den[4] = { 0, 0, 0, 0 };
  for (std::size_t i = 0; i < areas.size(); ++i)
  {
    const double w = areas[i];
    for (int c = 0; c < 4; ++c)
    {
      const double a = c < 3 ? estimate[i][c] : luminance(estimate[i]);
      const double r = c < 3 ? reference[i][c] : luminance(reference[i]);
      num[c] += w * (a - r) * (a - r);
      den[c] += w * r * r;
    }
  }
  ErrorMetrics m;
  for (int c = 0; c < 3; ++c)
    m.relRmse[c] = relativeError(num[c], den[c]);
  m.relRmseLuminance = relativeError(num[3], den[3]);
  return m;
}

Vec3f areaWeightedMean(const std::vector<Vec3f>& values, const std::vector<float>& areas)
{
  checkSizes(values.size(), areas.size(), "areaWeightedMean");
  double sum[3] = { 0, 0, 0 }, total = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    total += areas[i];
    for (int c = 0; c < 3; ++c)
      sum[c] += static_cast<double>(areas[i]) * values[i][c];
  }
  if (!(total > 0.0))
    return Vec3f(0.f);
  return { static_cast<float>(sum[0] / total), static_cast<float>(sum[1] / total),
    static_cast<float>(sum[2] / total) };
}
}
