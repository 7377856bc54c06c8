#include "shared/Bounce.h"

#include <gtest/gtest.h>

using namespace linkgi;

namespace
{
SparseMatrix denseToCsr(const std::vector<std::vector<float>>& dense)
{
  SparseMatrix m;
  m.rowOffsets.push_back(0);
  for (const auto& row : dense)
  {
    for (std::size_t c = 0; c < row.size(); ++c)
    {
      if (row[c] != 0.f)
      {
        m.columns.push_back(Index(c));
        m.weights.push_back(row[c]);
      }
    }
    m.rowOffsets.push_back(Index(m.columns.size()));
  }
  return m;
}
}

TEST(TestBounce, GatherMatchesDenseProduct)
{
  const std::vector<std::vector<float>> dense = { { 0, 1, 2 }, { 0.5f, 0, 0 }, { 0, 0, 0 } };
  const SparseMatrix m = denseToCsr(dense);
  const std::vector<Vec3f> x = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 } };
  std::vector<Vec3f> y(3);
  gatherRgb(m, x.data(), y.data());
  for (int r = 0; r < 3; ++r)
  {
    Vec3f expected(0.f);
    for (int c = 0; c < 3; ++c)
    {
      expected += x[c] * dense[r][c];
    }
    EXPECT_EQ(y[r], expected);
  }
}

TEST(TestBounce, ClosedEnclosureSumsTheGeometricSeries)
{
  // Two elements that see only each other (W = pi, like a closed furnace): with rho and Le,
  // n bounces give E_ind = pi Le (1 + rho + ... + rho^(n-1)).
  const SparseMatrix w = denseToCsr({ { 0, kPi }, { kPi, 0 } });
  BounceInputs in;
  in.fixedIrradiance.assign(2, Vec3f(0.f));
  in.albedo.assign(2, Vec3f(0.5f, 0.25f, 0.f));
  in.emission.assign(2, Vec3f(1.f));
  const std::vector<Vec3f> e = iterateBounces(w, in, 4);
  const auto series = [](float rho) { return 1.f + rho + rho * rho + rho * rho * rho; };
  EXPECT_NEAR(e[0].x, kPi * series(0.5f), 1e-4f);
  EXPECT_NEAR(e[0].y, kPi * series(0.25f), 1e-4f);
  EXPECT_NEAR(e[1].z, kPi, 1e-5f);
}

TEST(TestBounce, DirectLightBouncesOnce)
{
  // Element 0 receives E_d = 2 and reflects rho/pi of it; element 1 gathers it through W.
  const SparseMatrix w = denseToCsr({ { 0, 0 }, { 0.5f, 0 } });
  BounceInputs in;
  in.fixedIrradiance = { Vec3f(2.f), Vec3f(0.f) };
  in.albedo.assign(2, Vec3f(0.6f));
  const std::vector<Vec3f> e = iterateBounces(w, in, 3);
  EXPECT_NEAR(e[1].x, 0.5f * 0.6f / kPi * 2.f, 1e-6f);
  EXPECT_EQ(e[0], Vec3f(0.f));
}

TEST(TestBounce, SmoothingKeepsConstantsAndFeatures)
{
  // A folded strip: vertices 0-1-2 flat, 2-3 folded by 90 degrees (normals differ).
  const std::vector<Triangle> tris = { { { 0, 1, 2 } }, { { 1, 2, 3 } } };
  const Topology topo = Topology::build(4, tris);
  const std::vector<Vec3f> normals = { { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 1, 0, 0 } };
  const Elements el{ 4, false };
  const std::vector<Vec3f> constant(4, Vec3f(3.f));
  for (const Vec3f& v : smoothFeatureAware(constant, topo, normals, el, std::cos(0.5f)))
  {
    EXPECT_NEAR(v.x, 3.f, 1e-6f);
  }
  const std::vector<Vec3f> step = { Vec3f(1.f), Vec3f(1.f), Vec3f(1.f), Vec3f(10.f) };
  const std::vector<Vec3f> s = smoothFeatureAware(step, topo, normals, el, std::cos(0.5f));
  EXPECT_EQ(s[3], Vec3f(10.f)); // across the fold: not averaged
  EXPECT_EQ(s[0], Vec3f(1.f));
}
