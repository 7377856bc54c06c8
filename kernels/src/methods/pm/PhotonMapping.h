// Photon mapping with clustered final gather (Wang, Wang, Zhou & Guo 2009), per vertex: the
// pieces the CPU backend (PmCpu.cpp) runs, testable on their own. Photons are the shared
// light paths (shared/LightPaths.h traceLightPath): each stores the flux it reflects at a
// diffuse hit. The vertices are clustered (adaptive seeding + k-means with the paper's
// metric); only each cluster's sample vertex gathers (final gather against radiance
// estimates of the photon map); every vertex interpolates its neighbours' samples with
// irradiance-caching weights. See Documentation/Methods.md, "Photon mapping".
#pragma once

#include "methods/pm/PmMath.h"
#include "methods/pm/PointTree.h"

#include "shared/LightPaths.h"
#include "shared/Surface.h"

#include "cpu/Parallel.h"
#include "shared/RayTracer.h"
#include "linkgi/Scene.h"
#include "linkgi/SolverTypes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace linkgi::pm
{
/// What both backends fix: radiance estimates at every 4th photon (Christensen's
/// precomputed estimates), at most kMaxSites of them (an exact 64-nearest search is the
/// photon stage's largest cost; more photons make each estimate sharper instead), from
/// photons and read by gather rays within kEstimateRadius; Lloyd iterations of the
/// clustering; caustic photons count within kCausticRadius of a vertex. Radii are fractions
/// of the bounding-box diagonal.
constexpr std::uint32_t kMaxSites = 65536;
constexpr float kEstimateRadius = 0.05f;
constexpr int kMeansIterations = 4;
constexpr float kCausticRadius = 0.02f;
/// Every siteStride(n)-th of n photons holds an estimate.
inline std::uint32_t siteStride(std::size_t photons)
{
  return std::uint32_t(std::max<std::size_t>(4, (photons + kMaxSites - 1) / kMaxSites));
}

/// The global photon map: photons, and outgoing radiance estimates at every `siteStride`-th
/// photon (Christensen's precomputed estimates, which stand in for the paper's illumination
/// cut: a gather ray reads the nearest estimate instead of searching photons).
struct PhotonMap
{
  std::vector<Vec3f> positions, normals; ///< photon i: where, and the side it arrived on
  std::vector<Vec3f> flux;               ///< the flux it reflects (W), albedo applied
  std::vector<Vec3f> sitePositions, siteNormals;
  /// The radiance a diffuse surface reflects there (siteRadiance, PmMath.h: Jensen's
  /// estimate from the k nearest photons).
  std::vector<Vec3f> siteRadiance;
  std::vector<float> siteRadius2; ///< the squared radius of the disc each estimate's photons came from
  PointTree sites;
  float maxDistance2 = 3.4e38f; ///< of the photons an estimate counts, of the estimate a gather ray reads
  /// The caustic map: the photons that met only mirrors and glass between their light and
  /// this diffuse hit (also in the global map above), with the flux each reflects.
  std::vector<Vec3f> causticPositions, causticNormals, causticFlux;

  std::size_t count() const { return positions.size(); }
  /// Total reflected flux (W): what conservation tests check.
  Vec3f totalFlux() const;
  /// The estimates as the gather reads them (lookupRadiance, PmTypes.h).
  RadianceSitesView sitesView() const;
};

/// Instant radiosity's light-path set-up (sources, the scene's view) with the scene's
/// mirrors and glass: what photons and the final gather trace through, on either backend.
paths::PathSetup pathSetup(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const SolverOptions& options);

/// The photons of `options` (PhotonMappingOptions::photons, bounces, seed, sides): instant
/// radiosity's light paths from every source, with Russian roulette by albedo, into `map`'s
/// positions, normals and flux (its estimates are estimateRadiance's). `secondPassBytes`:
/// as traceVplsCpu's; returns what a second pass took (VplSet::secondPassBytes).
std::uint64_t tracePhotons(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer,
  const SolverOptions& options, PhotonMap& map, const ProgressCallback& progress = {},
  std::uint64_t secondPassBytes = UINT64_MAX);

/// v made unit length, or `fallback` where v is zero.
inline Vec3f unitOr(const Vec3f& v, const Vec3f& fallback)
{
  const float l2 = dot(v, v);
  return l2 > 0.f ? v * (1.f / std::sqrt(l2)) : fallback;
}

/// At most this many pieces beyond the mesh's triangles measure the surface for the
/// estimates (surfacePieces).
constexpr std::uint32_t kSurfacePieces = 65536;

/// The mesh cut into pieces small enough to measure a disc's area by (photonArea): every
/// triangle whose longest edge is longer than that of a right isosceles triangle of area
/// A / kSurfacePieces (A the mesh's area) is cut by halving its longest edge until none is,
/// and the others stay whole; a sliver is cut along its length only. That edge is made longer
/// while the cuts would add more than kSurfacePieces pieces. Each piece has its corners, its
/// centroid, its area, the farthest its corners lie from its centroid (radii) and the
/// vertex normals interpolated there; `reach`: the largest of those radii.
struct SurfacePieces
{
  std::vector<Vec3f> centroids, corners, normals;
  std::vector<float> areas, radii;
  float reach = 0.f;
};
SurfacePieces surfacePieces(const Scene& scene);

/// surfacePieces and the kd-tree of their centroids: built with the geometry, read by
/// every photon stage after it.
struct SurfaceTree
{
  SurfacePieces pieces;
  PointTree tree;

  explicit SurfaceTree(const Scene& scene);
  SurfaceTree(const SurfaceTree&) = delete; // the tree points into `pieces`
  SurfaceView view(bool twoSided) const;
};

/// Builds the map's estimates from photons already in positions/normals/flux, at every
/// `siteStride`-th photon: siteRadiance (PmMath.h) from the k nearest photons within
/// `maxRadius`, those facing within 37 degrees of the site's normal counted, over the area
/// `surface` says they can cover.
void estimateRadiance(PhotonMap& map, const SurfaceView& surface, std::uint32_t k, std::uint32_t siteStride,
  float maxRadius, const ProgressCallback& progress = {});

/// The clusters of the vertices, and what interpolation needs from them.
struct Clusters
{
  std::vector<Index> sample;     ///< per cluster: the vertex that gathers for it
  std::vector<Index> assignment; ///< per vertex: its cluster
  /// Per vertex, up to kInterpolants clusters whose samples it interpolates (its own first),
  /// kInvalidIndex where there are fewer.
  static constexpr int kInterpolants = pm::kInterpolants;
  std::vector<Index> neighbours;
  std::size_t count() const { return sample.size(); }
};

/// The paper's metric between a point (x, n) and a centre (c, m): alpha |x - c| +
/// sqrt(2 - 2 n.m), with |x - c| in units of the scene's bounding-box diagonal.
float clusterMetric(const Vec3f& x, const Vec3f& n, const Vec3f& c, const Vec3f& m, float alphaOverDiagonal);

/// Adaptive seeding (seeds split among halves of a Morton-ordered vertex range in
/// proportion to each half's geometric variation under clusterMetric) and `iterations`
/// rounds of k-means; `k` clusters (at most the vertex count). Each cluster's sample is its
/// member closest to its centre.
Clusters clusterVertices(const Scene& scene, std::uint32_t k, float alpha, int iterations,
  const ProgressCallback& progress = {});

/// What the final gather at the samples gives.
struct SampleIrradiance
{
  std::vector<Vec3f> irradiance;      ///< per cluster: E at its sample (photon map + sky)
  std::vector<float> harmonicDistance; ///< per cluster: R_j, the harmonic mean hit distance
  std::uint64_t rays = 0;
};

/// Final gather: `directions` (a cosine-weighted set, makeDirectionSet) from the `side`
/// (+1 front, -1 back) of each sample vertex, twisted per element by `seed`; a hit reads the
/// photon map's radiance, a miss the environment, the back of a one-sided surface is black.
/// With `rows` (one flag per vertex, this side's elements), only the clusters whose sample is
/// such a row gather; the others get zero irradiance and distance.
SampleIrradiance finalGather(const Scene& scene, const std::vector<RayOrigin>& origins,
  const std::vector<Vec3f>& faceNormals, const RayTracer& tracer, const PhotonMap& map,
  const Clusters& clusters, const std::vector<Vec3f>& directions, std::uint32_t seed, float side,
  bool twoSided, const ProgressCallback& progress = {}, const std::uint8_t* rows = nullptr);

/// Caustic irradiance at every vertex: the k nearest caustic photons on its side within
/// `maxRadius` (the flux each reflects, over pi r^2, divided by the vertex's albedo); zero
/// without caustic photons. With `rows` (one flag per vertex), only those vertices.
std::vector<Vec3f> causticIrradiance(const Scene& scene, const PhotonMap& map, std::uint32_t k,
  float maxRadius, const ProgressCallback& progress = {}, const std::uint8_t* rows = nullptr);

/// The caustic reference: light tracing. `paths` light paths from the point, spot and
/// directional lights, each to its first diffuse hit through any mirrors and glass; a hit
/// after at least one of them splats its incident flux into the hit triangle's vertices'
/// hat functions (barycentric weight over the vertex's third of its triangles' area):
/// caustic irradiance per vertex (W/m^2) whose area integral is the caustic power. Unlike
/// the photon map it needs no density estimate, so it converges to the exact projection.
std::vector<Vec3f> causticReference(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer, std::uint32_t paths, std::uint32_t seed, const ProgressCallback& progress = {});

/// Every vertex's irradiance from its neighbours' samples, weighted as in irradiance
/// caching: w = 1 / (|x - s| / R + sqrt(2 - 2 n.n_s)) over samples facing the same way.
std::vector<Vec3f> interpolate(const Scene& scene, const Clusters& clusters, const SampleIrradiance& samples);
}

namespace linkgi
{
/// The caustics' reference (Solution::caustics), photon mapping's own ground truth (the
/// path tracer cannot reach a point light through glass): `paths` light paths
/// from the lights through mirrors and glass to their first diffuse hit, the incident flux
/// splatted into the vertices' hat functions (W/m^2 per vertex; zero without specular
/// triangles). Validates a copy of `scene` (as the solver does, so the vertices match).
std::vector<Vec3f> solveCausticReference(const Scene& scene, std::uint32_t paths, std::uint32_t seed = 0);
}
