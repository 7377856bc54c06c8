// The reference path tracer as a method (Method::Reference): ground truth on the user's own
// data, through the same filter, progress bar and abort as the other methods. Two stages: the
// ray tracer (kept while the geometry stands) and the paths; nothing else is cached, since a
// new light or albedo changes every path. No smoothing: it would bias the ground truth.
#include "methods/reference/Reference.h"

#include "cpu/CpuGeometry.h"
#include "engine/Pipeline.h"
#include "linkgi/Error.h"

#include <string>

namespace linkgi::reference
{
namespace
{
using namespace engine;

enum Stage : std::size_t
{
  kGeometryStage, ///< topology, ray origins, face normals and the ray tracer
  kPathStage      ///< direct light and paths from every element
};

class CpuBackend final : public MethodBackend
{
public:
  void run(std::size_t index, const StageContext& c) override
  {
    if (index == kGeometryStage)
    {
      geometry.update(c);
      return;
    }
    ReferenceOptions ro;
    ro.pathsPerVertex = c.options.reference.pathsPerVertex;
    ro.bounces = c.options.bounces;
    ro.seed = c.options.seed;
    ro.twoSided = c.options.twoSided;
    ReferenceSolution r = solveReference(c.scene, *geometry.tracer, ro, c.progress);
    paths = std::uint64_t(r.indirect.size()) * ro.pathsPerVertex;
    writeSolution(c, std::move(r.indirect), r.direct);
  }
  void commit() override {}
  bool discard() override { return true; } // the tracer follows the scene it was built on
  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.setCounter("Paths", paths);
  }

  const RayTracer* sceneTracer() const override { return geometry.tracer.get(); }

private:
  CpuGeometry geometry;
  std::uint64_t paths = 0;
};

class ReferenceMethod final : public MethodSpec
{
public:
  const char* name() const override { return "reference"; }
  const std::vector<StageSpec>& stages() const override
  {
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 1.0 },
      { "Paths", "PathRuns", kEverything, 1u << kGeometryStage, 99.0 },
    };
    return table;
  }
  void validateOptions(const SolverOptions& o) const override
  {
    if (o.reference.pathsPerVertex < 1 || o.reference.pathsPerVertex > (1u << 20))
    {
      throw Error("Reference: the paths per vertex must be between 1 and 1048576; got " +
        std::to_string(o.reference.pathsPerVertex) + ".");
    }
  }
  void checkCombination(const SolverOptions& o) const override
  {
    if (o.partition)
    {
      throw Error("The reference method runs in one process; solve it without MPI partitions.");
    }
  }
  bool optionsDiffer(const SolverOptions& a, const SolverOptions& b) const override
  {
    return a.reference.pathsPerVertex != b.reference.pathsPerVertex;
  }
  std::string sampling(const SolverOptions& o) const override
  {
    return std::to_string(o.reference.pathsPerVertex) + " paths per vertex";
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions&) const override
  {
    return std::make_unique<CpuBackend>();
  }
  MemoryEstimate estimateMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t,
    bool) const override
  {
    // The geometry, the solution's arrays and per thread one wavefront of paths (small).
    MemoryEstimate m;
    m.hostBytes = cpuGeometryBytes(shape) + cpuSolutionBytes(shape, o);
    return m;
  }
};
}

const MethodSpec& referenceMethod()
{
  static const ReferenceMethod method;
  return method;
}
}
