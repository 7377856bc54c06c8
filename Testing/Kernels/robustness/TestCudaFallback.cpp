// The CPU fallback of the CUDA backend, on any machine: engine::ScopedCudaFactory stands in
// for the GPU (a device that is found, then a backend that cannot be made, or whose stage
// runs out of memory in the middle of an update). The orchestrator must fall back to the
// CPU, say so in stats().warnings and backendNote, and give bitwise the CPU's result; the
// next update tries the GPU again. (TestFaultsCuda covers the real GPU where one exists.)
#include "SceneFixtures.h"

#include "engine/CudaFactory.h"
#include "cuda/Cuda.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace linkgi;

namespace
{
SolverOptions onCuda(Method method)
{
  SolverOptions o;
  o.method = method;
  o.raysPerVertex = 16;
  o.bounces = 3;
  o.backend = Backend::Cuda;
  o.photonMapping.photons = 16384; // small: every stage fails in turn, each an update
  o.photonMapping.clusters = 256;
  o.photonMapping.gatherRays = 64;
  o.reference.pathsPerVertex = 16;
  return o;
}

/// The CPU backend posing as the GPU's: runs its stages, but throws the GPU's out of memory
/// at stage `failAt` while `*armed` is set.
class FailingBackend : public engine::MethodBackend
{
public:
  FailingBackend(std::unique_ptr<engine::MethodBackend> inner, std::size_t failAt, const bool* armed)
    : inner(std::move(inner)), failAt(failAt), armed(armed)
  {
  }
  void run(std::size_t index, const engine::StageContext& context) override
  {
    if (*armed && index == failAt)
    {
      throw CudaError("cudaMalloc: out of memory (test)", true);
    }
    inner->run(index, context);
  }
  void commit() override { inner->commit(); }
  bool discard() override { return inner->discard(); }
  void describe(SolverStats& stats) const override { inner->describe(stats); }

private:
  std::unique_ptr<engine::MethodBackend> inner;
  std::size_t failAt;
  const bool* armed;
};

bool contains(const std::vector<std::string>& lines, const std::string& words)
{
  for (const std::string& l : lines)
  {
    if (l.find(words) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

void expectSameBits(const Solution& a, const Solution& b)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  EXPECT_EQ(std::memcmp(a.radiance.data(), b.radiance.data(), a.radiance.size() * sizeof(Vec3f)), 0);
  EXPECT_EQ(std::memcmp(a.direct.data(), b.direct.data(), a.direct.size() * sizeof(Vec3f)), 0);
}

// Every registered method: the test's factories make a "CUDA" backend for each.
const std::vector<Method> kMethods = linkgi::methods();
}

TEST(CudaFallback, ABackendThatCannotBeMadeFallsBackToTheCpu)
{
  const Scene scene = test::roomWithBlock();
  for (const Method method : kMethods)
  {
    SCOPED_TRACE(int(method));
    SolverOptions cpu = onCuda(method);
    cpu.backend = Backend::Cpu;
    Solver reference;
    const Solution expected = reference.update(scene, cpu);

    engine::ScopedCudaFactory gpu({ [](std::string*) { return std::size_t(1); },
      [](const engine::MethodSpec&, const SolverOptions&) -> std::unique_ptr<engine::MethodBackend> {
        throw CudaError("no CUDA device can be used (test)", false);
      } });
    Solver solver;
    expectSameBits(solver.update(scene, onCuda(method)), expected);
    EXPECT_TRUE(contains(solver.stats().warnings, "The CUDA backend failed (no CUDA device can be used (test)); using the CPU."));
    EXPECT_EQ(solver.stats().backendNote, "CUDA failed; using the CPU.");
    EXPECT_EQ(solver.stats().backend, "cpu");
  }
}

TEST(CudaFallback, OutOfMemoryAtAnyStageFallsBackToTheCpuAndTheGpuIsTriedAgain)
{
  const Scene scene = test::roomWithBlock();
  for (const Method method : kMethods)
  {
    SolverOptions cpu = onCuda(method);
    cpu.backend = Backend::Cpu;
    Solver reference;
    const Solution expected = reference.update(scene, cpu);
    Scene brighter = scene;
    brighter.lights[0].intensity = brighter.lights[0].intensity * 2.f;
    const Solution expectedBrighter = reference.update(brighter, cpu);

    const std::size_t stages = engine::methodSpec(method).stages().size();
    for (std::size_t failAt = 0; failAt < stages; ++failAt)
    {
      SCOPED_TRACE(::testing::Message() << "method " << int(method) << " stage " << failAt);
      bool armed = true;
      int made = 0;
      engine::ScopedCudaFactory gpu({ [](std::string*) { return std::size_t(1); },
        [&](const engine::MethodSpec& spec, const SolverOptions& o) -> std::unique_ptr<engine::MethodBackend> {
          ++made;
          return std::make_unique<FailingBackend>(spec.createCpu(o), failAt, &armed);
        } });
      Solver solver;
      expectSameBits(solver.update(scene, onCuda(method)), expected);
      EXPECT_TRUE(contains(solver.stats().warnings, "out of memory (test)")) << solver.stats().backendNote;
      EXPECT_EQ(solver.stats().backendNote, "CUDA failed; using the CPU.");

      // The memory is back: the next update (a light change) runs on the "GPU" again, made
      // anew (the failed one was dropped), and agrees with the CPU.
      armed = false;
      expectSameBits(solver.update(brighter, onCuda(method)), expectedBrighter);
      EXPECT_TRUE(solver.stats().warnings.empty());
      EXPECT_NE(solver.stats().backendNote.find("using the GPU"), std::string::npos)
        << solver.stats().backendNote;
      EXPECT_EQ(made, 2);
    }
  }
}
