#include "engine/CpuGeometry.h"

#include "linkgi/Bounce.h"
#include "linkgi/Links.h"

#include <chrono>
#include <cmath>

namespace linkgi::engine
{
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
  if (o.smoothing)
  {
    const auto t = std::chrono::steady_clock::now();
    const float cosFeature = std::cos(o.featureAngleDegrees * (kPi / 180.f));
    indirect = smoothFeatureAware(indirect, topology, s.normals, elements, cosFeature);
    c.part("Smoothing", msSince(t));
  }
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
