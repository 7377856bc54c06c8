// What every CPU method's geometry stage keeps: one-ring topology, ray origins, front
// face normals and the ray tracer, brought up to date with the changes of an update.
#pragma once

#include "engine/Pipeline.h"

#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "scene/Topology.h"

namespace linkgi::engine
{
struct CpuGeometry
{
  std::unique_ptr<RayTracer> tracer;
  Topology topology;
  std::vector<RayOrigin> origins;
  std::vector<Vec3f> faceNormals;

  /// Rebuilds the topology on a topology change, the shifts and face normals always, and
  /// builds (topology) or refits (positions) the tracer; records the part "Topology" and
  /// the BVH counters. The tracer references the scene's arrays (RayTracer::build).
  void update(const StageContext& context);

  /// What every CPU backend reports the same way: "cpu", the tracer's name, no GPUs and
  /// nothing per device.
  void describe(SolverStats& stats) const;
};

/// Host bytes that CpuGeometry::update allocates on a mesh of `shape` at its peak: the
/// one-ring topology and its build, ray origins, face normals, and the tracer's BVH with
/// its build (Embree's or ours), and what a first update touches whatever the mesh (thread
/// stacks, arenas). Calibrated on measured peaks, not a bound; every CPU method's memory
/// estimate starts from this.
std::uint64_t cpuGeometryBytes(const MemoryShape& shape);

/// Host bytes of the per-element vectors that a CPU method's last stages hold at once when it
/// gathers E_ind per element (instant radiosity, photon mapping): E_d staged beside the
/// cached one, the environment and fixed irradiance, albedo, emission, the gathered and
/// smoothed E_ind and the solution's three arrays.
std::uint64_t cpuSolutionBytes(const MemoryShape& shape, const SolverOptions& options);

/// What a CPU method holds while it traces its light paths, the first stage after the
/// geometry: the geometry (and on a later update the previous solution, three vectors per
/// element, which a second pass dwarfs). A second pass of paths (traceVplsCpu) may take
/// what the budget leaves beyond it (memoryLeft), and the update's estimate is then at
/// least this and that pass (raiseEstimate).
std::uint64_t lightPathsHeldBytes(const StageContext& context);

/// The end of every CPU method's update, from its E_ind and E_d per element: feature-aware
/// smoothing where smoothingOn (the part "Smoothing"), then writeSolution.
void finishSolution(const StageContext& context, const Topology& topology, std::vector<Vec3f> indirect,
  const std::vector<Vec3f>& direct);

/// The solution from E_ind and E_d per element: both, and the outgoing radiance
/// L = Le + rho/pi (E_d + E_ind) (emission on front sides only).
void writeSolution(const StageContext& context, std::vector<Vec3f> indirect, const std::vector<Vec3f>& direct);
}
