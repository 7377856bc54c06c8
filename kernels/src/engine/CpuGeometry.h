// What every CPU method's geometry stage keeps: one-ring topology, ray-origin shifts, front
// face normals and the ray tracer, brought up to date with the changes of an update.
#pragma once

#include "engine/Pipeline.h"

#include "linkgi/RayTracer.h"
#include "linkgi/Topology.h"

namespace linkgi::engine
{
struct CpuGeometry
{
  std::unique_ptr<RayTracer> tracer;
  Topology topology;
  std::vector<Vec3f> shifts, faceNormals;

  /// Rebuilds the topology on a topology change, the shifts and face normals always, and
  /// builds (topology) or refits (positions) the tracer; records the part "Topology" and
  /// the BVH counters. The tracer references the scene's arrays (RayTracer::build).
  void update(const StageContext& context);
};
}
