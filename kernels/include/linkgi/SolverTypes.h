// What the solver takes (options) and gives (solution, statistics); no solver code here, so
// backends and tools can include it without the orchestrator.
#pragma once

#include "linkgi/Scene.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkgi
{
/// Called on the thread that started the work, between chunks: `fraction` in [0,1] of the
/// current stage. Return false to abort; the engine then throws linkgi::Aborted.
using ProgressCallback = std::function<bool(const char* stage, double fraction)>;

/// This process's share of a scene that several processes (MPI ranks) solve together, each
/// holding the whole scene: the CPU backend links or gathers only the rows (receiving
/// elements) marked here and completes each bounce's per-element vector through exchange(),
/// so the links, their memory and their time are split among the processes and the result
/// is the one process's, bit for bit. The GPU backend does not take partitions.
///
/// Every collective step first agrees on whether a process failed (`count`): a process that
/// fails between two steps (an abort, an error, memory) tells the others at their next step,
/// and they all leave the update together instead of waiting for it in an exchange
/// (together() below).
struct Partition
{
  /// Per element (vertices, then their back sides when two-sided): 1 = this process's row.
  std::vector<std::uint8_t> rows;
  /// The processes' collectives, all over one communicator, each called by every process at
  /// the same point of an update:
  /// the sum of a per-element RGB vector in which every process set its own rows and zeroed
  /// the others (an allreduce);
  std::function<void(std::vector<Vec3f>&)> sum;
  /// the smallest of one value (an allreduce of the minimum; empty: this process's own);
  std::function<std::uint64_t(std::uint64_t)> least;
  /// the sum of one count (an allreduce; empty: no process can tell the others of a failure).
  std::function<std::uint64_t(std::uint64_t)> count;

  /// Completes `values` (sum) once no process has failed; else throws PeerFailed.
  void exchange(std::vector<Vec3f>& values) const;
  /// The smallest `value` of the processes once no process has failed; else throws
  /// PeerFailed. Called at each check of the memory budget (once per update, twice where
  /// a method samples its memory): all processes refuse an update or all run it.
  std::uint64_t smallest(std::uint64_t value) const;
  /// One agreement step: throws PeerFailed when a process failed since the last one.
  void check() const;
  /// This process failed: its one agreement step, which the others take at their next
  /// collective step and leave by PeerFailed.
  void fail() const;
};

/// Runs `work`, one process's part of a collective update of the processes that share
/// `partition` (null: just runs it), so that they leave it together: when `work` throws on
/// some of them, it throws on all - the error itself where it happened, PeerFailed on the
/// others - and none is left waiting in an exchange. On success all have passed a last
/// agreement step. The outermost caller of a partitioned update wraps it in this, once.
void together(const Partition* partition, const std::function<void()>& work);

/// How the indirect light is computed. Every method writes the same Solution.
enum class Method
{
  Links, ///< the link structure of Schmitz, Tavenrath & Kobbelt 2008 (default)
  InstantRadiosity, ///< virtual point lights (Marques & Santos 2010): nothing precomputed
  ImplicitVisibility, ///< hierarchical links, visibility implied by the shortest link per
                      ///< direction bin (Dong, Kautz, Theobalt & Seidel 2007): no link rays
  PhotonMapping, ///< photons from the lights, final gather at clustered sample vertices
                 ///< (Wang, Wang, Zhou & Guo 2009)
  Reference ///< per-vertex Monte Carlo path tracing: the ground truth the others are
            ///< validated against (slow on purpose; SolverOptions::reference)
};

/// Options of Method::Reference; the other methods ignore them.
struct ReferenceMethodOptions
{
  /// Cosine-weighted paths per vertex (and back side): the first floor(sqrt(M))^2
  /// stratified. The noise of E_ind falls as 1/sqrt(M). 1 to 2^20. Default 1024.
  std::uint32_t pathsPerVertex = 1024;
};

/// Options of Method::PhotonMapping; the other methods ignore them.
struct PhotonMappingOptions
{
  /// Photons stored (about: light paths are traced until about this many diffuse hits).
  /// 1 to 2^24. Default 262144.
  std::uint32_t photons = 262144;
  /// Clusters of vertices; one sample vertex per cluster gathers. 1 to 2^20 (at most the
  /// vertex count is used). Default 12288: the interpolation between samples, not their
  /// noise, made most of the error on scanned models and detailed rooms at 4096
  /// (Documentation/Methods.md, "Photon mapping's clusters").
  std::uint32_t clusters = 12288;
  /// Final-gather rays per sample vertex: a perfect square. Default 144.
  std::uint32_t gatherRays = 144;
  /// Photons per radiance estimate (k nearest). 2 to 1024. Default 64.
  std::uint32_t estimatePhotons = 64;
  /// The clustering metric's weight of distance (in bounding-box diagonals) against normal
  /// change; the paper uses 0.1 to 0.5. Default 0.3.
  float alpha = 0.3f;
};
bool operator==(const PhotonMappingOptions& a, const PhotonMappingOptions& b);
inline bool operator!=(const PhotonMappingOptions& a, const PhotonMappingOptions& b)
{
  return !(a == b);
}

/// Options of Method::ImplicitVisibility; the other methods ignore them.
struct ImplicitVisibilityOptions
{
  /// N: each of the six faces of every element's cube map of directions has N x N bins
  /// (6 N^2 in all); a bin keeps the shortest link, and clusters are subdivided until they
  /// cover at most a bin. The paper uses 8, 12 or 16. 2 to 32. Default 12.
  std::uint32_t binsPerSide = 12;
};
bool operator==(const ImplicitVisibilityOptions& a, const ImplicitVisibilityOptions& b);
inline bool operator!=(const ImplicitVisibilityOptions& a, const ImplicitVisibilityOptions& b)
{
  return !(a == b);
}

/// Options of Method::InstantRadiosity; the other methods ignore them.
struct InstantRadiosityOptions
{
  /// Virtual point lights per update, about: ceil(vplCount / bounces) light paths leave the
  /// lights, emissive surfaces and environment, each leaving a VPL at up to `bounces`
  /// diffuse hits. At least 1, at most 1 << 20. Default 1024.
  std::uint32_t vplCount = 1024;
  /// d_min of the smoothstep bound of the geometry term, as a fraction of the scene's
  /// bounding-box diagonal: a VPL's contribution fades from full at 1.2 d_min to none at
  /// 0.8 d_min, so VPLs next to a vertex do not spike (this loses the light of short
  /// paths, which `compensationRays` take back; see Documentation/Methods.md). In [0, 1].
  /// Default 0.02: with the compensation on, a larger clamp only removes 1/d^2 noise (what
  /// is seen of the scanned models: 10% at 0.01, 7-7.5% at 0.02), until corners lose light
  /// the compensation cannot take back (the tearoom: 2.8% at 0.02, 8.4% at 0.05).
  float clampDistance = 0.02f;
  /// Interleaved sampling: the VPLs are split into this many subsets and each vertex gathers
  /// one of them (times the count); the feature-aware one-ring smoothing recombines them.
  /// 1 = every vertex gathers every VPL. 1 to 64. Default 1.
  std::uint32_t interleave = 1;
  /// Imperfect visibility: VPL shadow rays test a coarse proxy of the mesh (vertex
  /// clustering on a grid of proxyResolution cells along the longest box axis) instead of
  /// the mesh itself. Default off.
  bool proxyVisibility = false;
  /// Grid cells along the longest axis of the proxy's vertex clustering, 2 to 4096.
  /// Default 32.
  std::uint32_t proxyResolution = 32;
  /// Bias compensation: cosine-weighted rays per vertex (a perfect square, at most 1024)
  /// that recover the light the clamp takes, from the surfaces nearer than the clamp, with
  /// the update's own per-vertex radiance there (after Kollig & Keller 2004; see
  /// Documentation/Methods.md). 0: off, that light is lost. Default 64.
  std::uint32_t compensationRays = 64;
  /// Russian roulette: a light path continues past a hit with probability max(rho) and
  /// carries rho / max(rho) (unbiased, fewer VPLs); `bounces` still caps its length. Off
  /// (default): every path runs all its bounces carrying rho.
  bool russianRoulette = false;
};
bool operator==(const InstantRadiosityOptions& a, const InstantRadiosityOptions& b);
inline bool operator!=(const InstantRadiosityOptions& a, const InstantRadiosityOptions& b)
{
  return !(a == b);
}

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
  Gpu,    ///< built on the GPU (PLOC on size-extended Morton keys) in ~1-2 ms (default)
  HostSah ///< a binned SAH tree built on the CPU: ~10% faster rays, ~100x the build
};

struct SolverOptions
{
  /// The solution method. Default Links.
  linkgi::Method method = linkgi::Method::Links;
  /// n_C: directions per vertex, a perfect square k*k (traced in 4x4 blocks). Default 256.
  std::uint32_t raysPerVertex = 256;
  /// n_B: Jacobi bounces of indirect light. Default 3.
  std::uint32_t bounces = 3;
  /// Feature-aware one-ring smoothing of the indirect irradiance (Eq. 5-6): each vertex
  /// becomes the mean of its one-ring within the feature angle. It trades noise for blur
  /// across the ring, a bias that grows with the triangles' size. Default off: at the default
  /// sampling it raised the link method's error on every standard scene and scanned model
  /// (Documentation/Methods.md, "Smoothing"). Instant radiosity's interleaving smooths
  /// whatever this says (see smoothingOn), as do the coarse solutions of a progressive update.
  bool smoothing = false;
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
  /// CUDA: at most this many GPUs (0 = all of them). Default 0.
  int cudaDevices = 0;
  /// CUDA: BVH update on deformation. Default Auto.
  CudaBvhUpdate cudaBvhUpdate = CudaBvhUpdate::Auto;
  /// CUDA: where the BVH is built. Default Gpu.
  CudaBvhBuild cudaBvhBuild = CudaBvhBuild::Gpu;
  /// Method::InstantRadiosity's own options.
  InstantRadiosityOptions instantRadiosity;
  /// Method::ImplicitVisibility's own options.
  ImplicitVisibilityOptions implicitVisibility;
  /// Method::PhotonMapping's own options.
  PhotonMappingOptions photonMapping;
  /// Method::Reference's own options.
  ReferenceMethodOptions reference;
  /// Host memory an update may use, in bytes; an update estimated to need more is refused
  /// with an error that says what would fit, before anything is allocated. 0 (default):
  /// what the machine has available, less a margin (linkgi/Memory.h).
  std::uint64_t memoryBudget = 0;
  /// Under MPI: this process's rows (see Partition); null (default): all of them. Another
  /// Partition object, even an equal one, relinks.
  std::shared_ptr<const Partition> partition;
};

/// Every method this build has, in the order of the Method enum: what a user interface
/// offers and what tests iterate.
std::vector<Method> methods();

/// The name of `method` ("links", "instant-radiosity": SolverStats::method); throws
/// linkgi::Error for a value no registered method has.
const char* methodName(Method method);

/// The method called `name`; throws linkgi::Error naming the valid names.
Method methodByName(const std::string& name);

/// Every method's name, joined by `separator` ("links|instant-radiosity|...").
std::string methodNames(const std::string& separator = ", ");

/// Every field equal (a request for the same solve).
bool operator==(const SolverOptions& a, const SolverOptions& b);
inline bool operator!=(const SolverOptions& a, const SolverOptions& b)
{
  return !(a == b);
}

/// Whether an update with `o` smooths its indirect irradiance: `smoothing`, or instant
/// radiosity's interleaving, whose per-vertex subsets of the VPLs only the smoothing
/// recombines.
inline bool smoothingOn(const SolverOptions& o)
{
  return o.smoothing || (o.method == Method::InstantRadiosity && o.instantRadiosity.interleave > 1);
}

/// Checks the options every method shares; throws linkgi::Error naming the bad one. The one
/// home of these limits: the filter and the tools call it too.
void validateOptions(const SolverOptions& options);

/// Per-element results. Elements are the vertices; with two-sided elements the back sides
/// follow the front sides (element vertexCount + i is the back of vertex i).
struct Solution
{
  std::vector<Vec3f> direct;   ///< E_d: irradiance from the point, spot and directional lights
  std::vector<Vec3f> indirect; ///< E_ind: bounced light, emissive surfaces and environment
  std::vector<Vec3f> radiance; ///< outgoing L = Le + rho/pi (E_d + E_ind)
  /// Of E_ind, the light focused onto the element by mirrors and glass straight from the
  /// lights (caustics): Method::PhotonMapping on a scene with specular triangles; empty
  /// otherwise.
  std::vector<Vec3f> caustics;
  std::size_t elementCount() const { return direct.size(); }
};

/// One stage of the method that ran, or a named part of one (its time is not counted in the
/// stage's own), as the orchestrator records it.
struct StageStats
{
  std::string name;    ///< "Links": field data LinkGI.MsLinks, bench "Links"
  std::string counter; ///< lifetime run counter, "LinkBuilds"; empty for parts
  std::string parent;  ///< for a part: the stage it belongs to; empty for a stage
  bool ran = false;    ///< in the last update
  double ms = 0.0;     ///< last update, 0 if it did not run
  std::uint64_t runs = 0; ///< lifetime, over successful updates
};

/// What the last update computed and how long each stage took.
struct SolverStats
{
  /// The method's stages in pipeline order, and the parts their backends reported.
  std::vector<StageStats> stages;
  /// The stage or part called `name`; nullptr when the method has none.
  const StageStats* stage(const std::string& name) const;
  bool ran(const std::string& name) const;
  double ms(const std::string& name) const;
  /// Lifetime runs of the stage whose counter (or name) is `counter`.
  std::uint64_t runs(const std::string& counter) const;

  // The acceleration structure (every backend has one): which way it followed the last
  // geometry change, and lifetime totals.
  bool builtBvh = false, refitBvh = false;
  std::uint64_t bvhBuilds = 0, bvhRefits = 0;
  /// Receiving elements, rays of the indirect light's stage (link rays, gather or shadow
  /// rays to VPLs) and shadow rays to the lights, in the current solution.
  std::uint64_t elements = 0, rays = 0, lightRays = 0;
  /// Sizes the method that ran reports of its own structures, by name (field data
  /// LinkGI.<name>): "LinksRaw", "LinksCompressed", "LinkBytes" (the link methods;
  /// implicit visibility on the CPU also "LinksCreated", its node links before each bin kept
  /// its shortest, and "LinksEnvironment", its leaves' empty bins), "Vpls" (instant
  /// radiosity), "Photons", "Clusters" (photon mapping). Only the method's own.
  std::vector<std::pair<std::string, std::uint64_t>> counters;
  /// The counter called `name`, 0 when the method reports none.
  std::uint64_t counter(const std::string& name) const;
  /// Sets (or adds) the counter `name`.
  void setCounter(const std::string& name, std::uint64_t value);
  /// The whole last update in milliseconds.
  double msTotal = 0;
  /// Of msTotal: copying and validating the scene and finding what changed (host).
  double msPrepare = 0;
  std::vector<std::string> warnings; ///< from scene validation and backend fallbacks
  /// Which method and backend ran the last update ("links", "cpu" or "cuda"), on what
  /// ("embree", "2 x NVIDIA H200"), and why that backend (Auto's choice or a fallback).
  std::string method, backend, device, backendNote;
  int devices = 0;                         ///< GPUs the update used (0 on the CPU)
  std::vector<std::uint64_t> linkedPerDevice; ///< elements (rows) each GPU linked and holds
  /// Per GPU in the last link stage: batches, and milliseconds busy tracing, compressing
  /// (GPU time) and in all (its thread's wall time) - how well the batches balanced.
  std::vector<std::uint32_t> batchesPerDevice;
  std::vector<double> msTracePerDevice, msCompressPerDevice, msWallPerDevice;
  /// GPU memory the engine itself had allocated at its peak during the update, all GPUs
  /// together (not the device's total - free, which counts the CUDA context and others).
  std::uint64_t gpuBytesAllocated = 0;
  /// The method's estimate of the last update's peak memory (host, GPUs), and the host
  /// budget it was checked against (linkgi/Memory.h).
  std::uint64_t hostBytesEstimated = 0, deviceBytesEstimated = 0, memoryBudget = 0;
  /// What that estimate took from a sample of the mesh (MemoryShape::sampledPerElement; the
  /// link method on the CPU: links per row), 0 where it came from the sizes alone.
  double memorySampledPerElement = 0.0;
};
}
