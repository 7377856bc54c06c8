// The link-structure solver (Schmitz, Tavenrath & Kobbelt 2008) with caching by what changed.
#pragma once

#include "linkgi/Parallel.h"
#include "linkgi/Scene.h"

#include <memory>
#include <string>
#include <vector>

namespace linkgi
{
/// Where the solver runs.
enum class Backend
{
  Auto, ///< CUDA when this build has it and a CUDA device exists, else the CPU (default)
  Cpu,  ///< Embree and all cores
  Cuda  ///< the GPU(s); falls back to the CPU with a warning when no device or memory is left
};

/// CUDA backend: what a deformation (same triangles, moved vertices) does to the GPU's BVH.
enum class CudaBvhUpdate
{
  Auto,    ///< refit while the tree stays tight, rebuild once its box surface area has grown
           ///< by half since its build (boxes of a refit tree swell as the mesh deforms)
  Rebuild, ///< always a new linear BVH (a millisecond for 200k triangles)
  Refit    ///< always new boxes for the old tree
};

/// CUDA backend: where its BVH is built.
enum class CudaBvhBuild
{
  Gpu,    ///< a linear BVH built on the GPU in about a millisecond (default)
  HostSah ///< a binned SAH tree built on the CPU: ~30% fewer nodes per ray, ~100x the build
};

struct SolverOptions
{
  /// n_C: directions per vertex, a perfect square k*k (traced in 4x4 blocks). Default 256.
  std::uint32_t raysPerVertex = 256;
  /// n_B: Jacobi bounces of indirect light. Default 3.
  std::uint32_t bounces = 3;
  /// Feature-aware one-ring smoothing of the indirect irradiance (Eq. 5-6). Default on.
  bool smoothing = true;
  /// alpha_f: neighbours whose normals differ by more than this (degrees) are not averaged.
  float featureAngleDegrees = 30.f;
  /// Two-sided elements: every vertex also has a back side (normal -n) with its own value.
  /// Off (default): a ray hitting the back of a triangle is blocked and sees black.
  bool twoSided = false;
  /// Rotate the shared direction set by a random angle about each vertex normal, so the
  /// fixed pattern does not alias into structured artefacts. Default on.
  bool twist = true;
  /// Seed of the per-vertex twist angles; results are deterministic for a given seed.
  std::uint32_t seed = 0;
  /// Shadow rays also at the 1:4 subdivision points (edge midpoints) of the one-ring, so
  /// hard shadow edges do not alias onto vertices. Default on.
  bool lightOversampling = true;
  AlbedoPolicy albedoPolicy = AlbedoPolicy::Clamp;
  /// CPU, CUDA, or Auto (CUDA when a device exists). Default Auto.
  Backend backend = Backend::Auto;
  /// CUDA: link generation runs on at most this many GPUs (0 = all of them). Default 0.
  int cudaDevices = 0;
  /// CUDA: BVH update on deformation. Default Auto.
  CudaBvhUpdate cudaBvhUpdate = CudaBvhUpdate::Auto;
  /// CUDA: where the BVH is built. Default Gpu.
  CudaBvhBuild cudaBvhBuild = CudaBvhBuild::Gpu;
};

/// Per-element results. Elements are the vertices; with two-sided elements the back sides
/// follow the front sides (element vertexCount + i is the back of vertex i).
struct Solution
{
  std::vector<Vec3f> direct;   ///< E_d: irradiance from the point, spot and directional lights
  std::vector<Vec3f> indirect; ///< E_ind: bounced light, emissive surfaces and environment
  std::vector<Vec3f> radiance; ///< outgoing L = Le + rho/pi (E_d + E_ind)
  std::size_t elementCount() const { return direct.size(); }
};

/// What the last update computed and how long each stage took.
struct SolverStats
{
  // Which stages the last update ran.
  bool builtBvh = false, refitBvh = false, builtLinks = false, builtLightLinks = false,
       ranBounces = false;
  // Lifetime totals of the same, for tests and the filter's counters.
  std::uint64_t bvhBuilds = 0, bvhRefits = 0, linkBuilds = 0, lightLinkBuilds = 0, bounceRuns = 0;
  // Sizes of the current link structure.
  std::uint64_t elements = 0, rays = 0, linksRaw = 0, linksCompressed = 0, linkBytes = 0,
                lightRays = 0;
  // Stage times of the last update in milliseconds (0 for stages that did not run).
  double msBvh = 0, msLinks = 0, msCompress = 0, msLightLinks = 0, msBounces = 0,
         msSmoothing = 0, msTotal = 0;
  /// Of msTotal: copying and validating the scene and finding what changed (host).
  double msPrepare = 0;
  /// Of msBvh: one-ring topology, ray origin shifts and face normals (host).
  double msTopology = 0;
  std::vector<std::string> warnings; ///< from scene validation and backend fallbacks
  /// Which backend ran the last update ("cpu" or "cuda"), on what ("embree", "2 x NVIDIA
  /// H200"), and why that one (the Auto choice or the reason for a fallback to the CPU).
  std::string backend, device, backendNote;
  int devices = 0;                         ///< GPUs the link stage used (0 on the CPU)
  std::vector<std::uint64_t> linkedPerDevice; ///< elements each GPU linked, last link stage
  /// Per GPU in the last link stage: batches, and milliseconds busy tracing, compressing
  /// (GPU time) and in all (its thread's wall time) - how well the batches balanced.
  std::vector<std::uint32_t> batchesPerDevice;
  std::vector<double> msTracePerDevice, msCompressPerDevice, msWallPerDevice;
  std::uint64_t gpuPeakBytes = 0;          ///< most GPU memory in use during the update
};

/// Computes direct and multi-bounce indirect irradiance per vertex. Between updates it keeps
/// the acceleration structure, the link matrix and the direct light, and recomputes only
/// what the new scene and options invalidate:
///   lights only -> light links + bounces;   albedo/emission/environment -> bounces;
///   positions or normals -> refit + links + everything after;   triangles -> everything.
class Solver
{
public:
  Solver();
  ~Solver();
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  /// Solves `scene`. Throws linkgi::Error for invalid input and linkgi::Aborted when
  /// `progress` returns false; in both cases solution() still returns the previous result.
  const Solution& update(const Scene& scene, const SolverOptions& options = {},
    const ProgressCallback& progress = {});

  const Solution& solution() const;
  const SolverStats& stats() const;
  /// Forgets every cached stage; the next update recomputes everything.
  void reset();

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
}
