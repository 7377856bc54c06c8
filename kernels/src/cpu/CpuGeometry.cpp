#include "cpu/CpuGeometry.h"

#include "shared/Bounce.h"
#include "shared/Surface.h"

#include <chrono>
#include <cmath>

namespace linkgi::engine
{
namespace
{
/// The BVH and its build per triangle, as measured (Embree 3 on the standard scenes and
/// Testing/Data/Models, Documentation/Methods.md "Memory").
constexpr std::uint64_t kBvhBytesPerTriangle = 120;
/// What a first update touches whatever the mesh: the worker threads' stacks and arenas and
/// Embree's first blocks (the peak of a 1.6k-vertex scene less its arrays).
constexpr std::uint64_t kFirstUpdateBytes = std::uint64_t(2) << 20;
}

void CpuGeometry::update(const StageContext& c)
{
  const Scene& s = c.scene;
  const auto start = std::chrono::steady_clock::now();
  if (c.changes & kTopology)
  {
    topology = Topology::build(s.vertexCount(), s.triangles);
  }
  origins = rayOrigins(s, topology);
  faceNormals = frontFaceNormals(s);
  c.part("Topology", msSince(start));
  if (!tracer)
  {
    tracer = createCpuRayTracer();
  }
  if (c.changes & kTopology)
  {
    tracer->build(s.positions, s.triangles);
    c.stats.builtBvh = true;
    ++c.stats.bvhBuilds;
  }
  else if (c.changes & kPositions)
  {
    tracer->refit(s.positions);
    c.stats.refitBvh = true;
    ++c.stats.bvhRefits;
  }
}

std::uint64_t cpuGeometryBytes(const MemoryShape& shape)
{
  // Topology: ~3 neighbour, edge and vertex-edge entries per triangle and their sort;
  // per vertex the one-ring offsets and the origin shift; per triangle a face normal and
  // the BVH with its build.
  const std::uint64_t topology = 3 * (sizeof(Index) + sizeof(std::pair<Index, Index>) + sizeof(Index)) + 2 * 3 * sizeof(Index);
  return shape.triangles * (topology + sizeof(Vec3f) + kBvhBytesPerTriangle) +
    shape.vertices * (2 * sizeof(Index) + sizeof(RayOrigin)) + kFirstUpdateBytes;
}

std::uint64_t cpuSolutionBytes(const MemoryShape& shape, const SolverOptions& o)
{
  return shape.vertices * (o.twoSided ? 2 : 1) * sizeof(Vec3f) * 10;
}

std::uint64_t lightPathsHeldBytes(const StageContext& c)
{
  return cpuGeometryBytes(MemoryShape::of(c.scene));
}

void CpuGeometry::describe(SolverStats& st) const
{
  st.backend = "cpu";
  st.device = tracer ? tracer->name() : "";
  st.devices = 0;
  st.linkedPerDevice.clear();
  st.batchesPerDevice.clear();
  st.msTracePerDevice.clear();
  st.msCompressPerDevice.clear();
  st.msWallPerDevice.clear();
  st.gpuBytesAllocated = 0;
}

void finishSolution(const StageContext& c, const Topology& topology, std::vector<Vec3f> indirect,
  const std::vector<Vec3f>& direct)
{
  const Scene& s = c.scene;
  const SolverOptions& o = c.options;
  const Elements elements{ s.vertexCount(), o.twoSided };
  if (smoothingOn(o))
  {
    const auto t = std::chrono::steady_clock::now();
    const float cosFeature = std::cos(o.featureAngleDegrees * (kPi / 180.f));
    indirect = smoothFeatureAware(indirect, topology, s.normals, elements, cosFeature);
    c.part("Smoothing", msSince(t));
  }
  writeSolution(c, std::move(indirect), direct);
}

void writeSolution(const StageContext& c, std::vector<Vec3f> indirect, const std::vector<Vec3f>& direct)
{
  const Scene& s = c.scene;
  const Elements elements{ s.vertexCount(), c.options.twoSided };
  Solution& sol = c.solution;
  sol.direct = direct;
  sol.radiance.resize(elements.count());
  for (std::size_t e = 0; e < elements.count(); ++e)
  {
    const Index v = elements.vertexOf(e);
    const Vec3f le = (e < s.vertexCount() && !s.emission.empty()) ? s.emission[e] : Vec3f(0.f);
    sol.radiance[e] = outgoingRadiance(s.albedo[v], sol.direct[e], indirect[e], le);
  }
  sol.indirect = std::move(indirect);
}
}
