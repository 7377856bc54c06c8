// The CUDA backend's acceptance checks on the standard scenes: the same scene, rays and seed
// give the CPU engine's answer within 1% per vertex, and the closed furnace converges to
// Le / (1 - rho) on the GPU.
#include "CudaFixtures.h"

#include "linkgi/Scenes.h"

using namespace linkgi;
using namespace linkgi::test;

TEST(CudaScenes, CornellAgreesWithTheCpuEngine)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  expectBackendsAgree(makeStandardScene("cornell"), SolverOptions{}, 0.01f);
}

TEST(CudaScenes, TearoomAgreesWithTheCpuEngine)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  expectBackendsAgree(makeStandardScene("tearoom"), SolverOptions{}, 0.01f);
}

TEST(CudaScenes, FurnaceConvergesToLeOverOneMinusRho)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  // As TestAnalytic's furnace: 12 bounces leave 1.2e-4 of the geometric series.
  const Scene s = makeStandardScene("furnace");
  SolverOptions o = onBackend(Backend::Cuda);
  o.bounces = 12;
  Solver solver;
  const Solution& sol = solver.update(s, o);
  ASSERT_EQ(solver.stats().backend, "cuda");
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
