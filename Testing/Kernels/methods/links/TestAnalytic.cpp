// The solver against closed-form answers and against the path-traced reference.
#include "SceneFixtures.h"

#include "shared/Metrics.h"
#include "methods/reference/Reference.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

using namespace linkgi;

TEST(TestAnalytic, FurnaceConvergesToLeOverOneMinusRho)
{
  // Closed sphere, rho = 0.5, Le = 1: L = Le / (1 - rho) = 2. After n_B bounces the missing
  // tail is rho^(n_B+1) / (1 - rho) relative; 12 bounces leave 1.2e-4.
  const Scene s = makeStandardScene("furnace");
  SolverOptions o;
  o.bounces = 12;
  Solver solver;
  const Solution& sol = solver.update(s, o);
  const std::vector<float> area = vertexAreas(s);
  double mean = 0, total = 0;
  for (std::size_t v = 0; v < s.vertexCount(); ++v)
  {
    const float expected = s.emission[v].x / (1.f - s.albedo[v].x);
    ASSERT_NEAR(sol.radiance[v].x / expected, 1.f, 0.02f) << "vertex " << v;
    mean += area[v] * sol.radiance[v].x / expected;
    total += area[v];
  }
  EXPECT_NEAR(mean / total, 1.0, 0.005);
}

namespace
{
/// Area-weighted mean irradiance on the receiver square / pi = form factor receiver->emitter.
double formFactor(bool perpendicular)
{
  const Scene s = test::twoSquares(perpendicular, 32);
  SolverOptions o;
  o.raysPerVertex = 1024;
  o.bounces = 1;
  Solver solver;
  const Solution& sol = solver.update(s, o);
  const std::vector<float> area = vertexAreas(s);
  double e = 0, a = 0;
  for (std::size_t v = s.vertexCount() / 2; v < s.vertexCount(); ++v)
  {
    e += area[v] * sol.indirect[v].x;
    a += area[v];
  }
  return e / a / kPi;
}
}

TEST(TestAnalytic, ParallelSquaresFormFactor)
{
  EXPECT_NEAR(formFactor(false) / 0.1998, 1.0, 0.02);
}

TEST(TestAnalytic, PerpendicularSquaresFormFactor)
{
  EXPECT_NEAR(formFactor(true) / 0.2000, 1.0, 0.02);
}

namespace
{
std::vector<Vec3f> total(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b)
{
  std::vector<Vec3f> t(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    t[i] = a[i] + b[i];
  }
  return t;
}
}

TEST(TestAnalytic, CornellBoxAgreesWithReference)
{
  // Total irradiance E_d + E_ind against per-vertex path tracing with 16 x 256 paths and the
  // same bounce count; and the error must shrink when n_C grows from 16 to 256.
  const Scene s = makeStandardScene("cornell");
  ReferenceOptions ro;
  ro.pathsPerVertex = 16 * 256;
  ro.bounces = 3;
  const ReferenceSolution ref = solveReference(s, ro);
  const std::vector<Vec3f> reference = total(ref.direct, ref.indirect);
  const std::vector<float> area = vertexAreas(s);
  double previous = 1e9;
  for (std::uint32_t rays : { 16u, 256u })
  {
    SolverOptions o;
    o.raysPerVertex = rays;
    o.bounces = ro.bounces;
    Solver solver;
  const Solution& sol = solver.update(s, o);
    const ErrorMetrics err = relativeRmse(total(sol.direct, sol.indirect), reference, area);
    std::printf("cornell n_C=%u: relative RMSE luminance %.4f (r %.4f g %.4f b %.4f)\n", rays,
      err.relRmseLuminance, err.relRmse.x, err.relRmse.y, err.relRmse.z);
    if (rays == 256)
    {
      EXPECT_LE(err.relRmseLuminance, 0.05);
      EXPECT_LE(maxComponent(err.relRmse), 0.05f);
    }
    EXPECT_LT(err.relRmseLuminance, previous);
    previous = err.relRmseLuminance;
  }
}
