// Helpers of the CUDA backend tests: skipping without a GPU, and comparing solutions.
#pragma once

#include "cuda/Cuda.h"
#include "shared/Metrics.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <string>

/// Skips the test (with the reason) where this build or machine has no CUDA device.
#define LINKGI_REQUIRE_CUDA_DEVICE()                                                              \
  do                                                                                              \
  {                                                                                               \
    std::string whyNot;                                                                           \
    if (::linkgi::cuda::devices(&whyNot).empty())                                                 \
    {                                                                                             \
      GTEST_SKIP() << "CUDA backend test skipped: " << whyNot;                                    \
    }                                                                                             \
  } while (false)

namespace linkgi::test
{
inline SolverOptions onBackend(Backend backend, SolverOptions o = {})
{
  o.backend = backend;
  return o;
}

/// Worst channel of the per-vertex (unweighted) relative RMSE of a against b.
inline float relativeError(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b)
{
  const std::vector<float> ones(a.size(), 1.f);
  return maxComponent(relativeRmse(a, b, ones).relRmse);
}

/// The same scene, rays and seed on the CPU and on the GPU: every output within `tolerance`.
inline void expectBackendsAgree(const Scene& s, SolverOptions o, float tolerance)
{
  Solver cpu, gpu;
  const Solution& a = cpu.update(s, onBackend(Backend::Cpu, o));
  const Solution& b = gpu.update(s, onBackend(Backend::Cuda, o));
  ASSERT_EQ(gpu.stats().backend, "cuda") << gpu.stats().backendNote;
  ASSERT_EQ(a.elementCount(), b.elementCount());
  EXPECT_LE(relativeError(b.direct, a.direct), tolerance);
  EXPECT_LE(relativeError(b.indirect, a.indirect), tolerance);
  EXPECT_LE(relativeError(b.radiance, a.radiance), tolerance);
  EXPECT_EQ(gpu.stats().rays, cpu.stats().rays);
  // Same hits merge into the same links; a handful of rays may graze an edge differently.
  EXPECT_NEAR(double(gpu.stats().counter("LinksCompressed")), double(cpu.stats().counter("LinksCompressed")),
    1e-3 * cpu.stats().counter("LinksCompressed"));
  EXPECT_NEAR(double(gpu.stats().lightRays), double(cpu.stats().lightRays), 1e-3 * cpu.stats().lightRays + 1);
}
}
