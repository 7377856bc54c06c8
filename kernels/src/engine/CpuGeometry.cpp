#include "engine/CpuGeometry.h"

#include "linkgi/Links.h"

#include <chrono>

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
  shifts = originShifts(s, topology);
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
}
