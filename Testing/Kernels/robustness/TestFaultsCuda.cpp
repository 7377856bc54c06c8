// The GPU out of memory in the middle of an update: every allocation of a full update in
// turn fails (cuda::failAllocation, the engine's fault injection), the solver falls back to
// the CPU with a warning that says so, frees what the GPU backend held, publishes exactly
// the CPU's solution, and uses the GPU again for the next update. Skips without a GPU.
#include "SceneFixtures.h"

#include "cuda/CudaCheck.h"
#include "cuda/GPUBuffer.h"

#include "cuda/Cuda.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace linkgi;

TEST(TestFaultsCuda, OutOfMemoryInTheMiddleOfAnUpdateFallsBackToTheCpu)
{
  if (cuda::devices().empty())
  {
    GTEST_SKIP() << "needs a CUDA device";
  }
  SolverOptions gpu, cpu;
  gpu.raysPerVertex = cpu.raysPerVertex = 64;
  gpu.backend = Backend::Cuda;
  cpu.backend = Backend::Cpu;
  const Scene room = test::roomWithBlock(), finer = test::roomWithBlock(0.2f);
  Solver reference;
  const Solution expected = reference.update(finer, cpu);

  std::size_t n = 1;
  for (; n < 1000; ++n)
  {
    SCOPED_TRACE(n);
    Solver solver;
    solver.update(room, gpu);
    ASSERT_EQ(solver.stats().backend, "cuda");
    // A new mesh: every GPU buffer grows, the n-th allocation of the update fails.
    cuda::failAllocation(n);
    solver.update(finer, gpu);
    const bool failed = cuda::allocationsBeforeFailure() == 0;
    cuda::failAllocation(0);
    if (!failed)
    {
      EXPECT_EQ(solver.stats().backend, "cuda");
      break; // the update needed fewer than n allocations: every one has failed once
    }
    ASSERT_EQ(solver.stats().backend, "cpu");
    bool said = false;
    for (const std::string& w : solver.stats().warnings)
    {
      said |= w.find("out of memory") != std::string::npos && w.find("using the CPU") != std::string::npos;
    }
    EXPECT_TRUE(said) << "no warning names the GPU's memory";
    EXPECT_EQ(cuda::MemoryLedger::held(), 0u) << "the failed GPU backend kept memory";
    const Solution& s = solver.solution();
    ASSERT_EQ(s.elementCount(), expected.elementCount());
    EXPECT_EQ(std::memcmp(s.radiance.data(), expected.radiance.data(), sizeof(Vec3f) * s.elementCount()), 0);

    // The next update is the GPU's again.
    Scene lit = finer;
    lit.lights[0].position.x += 0.05f;
    solver.update(lit, gpu);
    EXPECT_EQ(solver.stats().backend, "cuda");
  }
  EXPECT_GT(n, 3u) << "an update of a new mesh allocates more than a few buffers";
  EXPECT_LT(n, 1000u);
}
