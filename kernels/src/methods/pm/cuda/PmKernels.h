// Launchers of photon mapping's CUDA kernels: host-callable, no __global__ here. The
// per-item math is pm/PmMath.h's and the searches pm/PmTypes.h's, the same the CPU runs;
// light paths are cuda/LightPathKernels.h's.
#pragma once

#include "methods/pm/PmMath.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"

#include <initializer_list>
#include <utility>

namespace linkgi::pm::gpu
{
/// The implicit median kd-tree of PointTree (PmTypes.h) over device points, built level by
/// level: each range's split axis is the longest side of a sample of its points' box, and
/// a sort along it puts the median at the range's middle (one radix sort of the whole array
/// while the ranges are large, a segmented sort once they are small). The split axes can
/// differ from PointTree's (it boxes every point); what a search finds does not.
class DevicePointTree
{
public:
  /// Indexes `points` (device, `count` of them; they must outlive the tree). No wait.
  void build(const Vec3f* points, std::uint32_t count, cudaStream_t stream);
  PointTreeView view() const;
  /// Copies arrays of the points' attributes in the tree's order (out[i] = in[order[i]]),
  /// the positions first, and returns the view of the tree over the copied positions
  /// (without `order`): a search then reads neighbours from neighbouring memory. No wait.
  PointTreeView inTreeOrder(std::initializer_list<std::pair<const Vec3f*, Vec3f*>> arrays, cudaStream_t stream) const;
  /// The same for one array of floats. No wait.
  void inTreeOrder(const float* in, float* out, cudaStream_t stream) const;
  std::uint32_t size() const { return count; }

private:
  const Vec3f* points = nullptr;
  std::uint32_t count = 0;
  cuda::GPUBuffer<Index> order, orderOut;
  cuda::GPUBuffer<std::uint8_t> axes;
  cuda::GPUBuffer<float> keys, keysOut;
  cuda::GPUBuffer<std::uint64_t> wideKeys, wideKeysOut; ///< the levels sorted as one array
  cuda::GPUBuffer<std::uint32_t> begins, ends, nextBegins, nextEnds;
  cuda::GPUBuffer<std::uint8_t> rangeAxes; ///< per range of the level being split
  cuda::GPUBuffer<unsigned char> temp;
};

/// The photon map's arrays on the device: every photon, and the caustic ones.
struct DevicePhotons
{
  cuda::GPUBuffer<Vec3f> positions, normals, flux;
  cuda::GPUBuffer<Vec3f> causticPositions, causticNormals, causticFlux;
};

/// Splits `count` packed light-path hits into photons (every non-sky one, in order) and
/// caustic photons (those with the caustic flag), into `out`, sized for all `count`.
/// `flags`, `scan`, `temp`: scratch. `totals` (pinned host memory, 2 entries) gets how many
/// of each: the caller reads them after a wait.
void splitPhotons(const paths::Vpl* hits, std::size_t count, DevicePhotons& out, cuda::GPUBuffer<Index>& flags,
  cuda::GPUBuffer<Offset>& scan, cuda::GPUBuffer<unsigned char>& temp, Offset* totals, cudaStream_t stream);

/// Radiance estimates (siteRadiance) and the squared radii of their discs at every `stride`-th
/// photon, with k (2 to 1024) photons each within sqrt(max2): ceil(count / stride) sites,
/// written in the tree's order (so that a
/// warp searches one neighbourhood). `photons`: the map in tree order (inTreeOrder); `order`:
/// the photon numbers at the tree positions (view().order), which say which are sites;
/// `surface`: the pieces of the mesh the estimates measure their discs by. `scratch`, `scan`,
/// `temp`: scratch.
void estimateSites(const PhotonsView& photons, const Index* order, const SurfaceView& surface, std::uint32_t stride,
  std::uint32_t k, float max2, Vec3f* sitePositions, Vec3f* siteNormals, Vec3f* siteRadiance, float* siteRadius2,
  cuda::GPUBuffer<Index>& scratch, cuda::GPUBuffer<Offset>& scan, cuda::GPUBuffer<unsigned char>& temp,
  cudaStream_t stream);

/// What the final gather reads on the device.
struct GatherLaunch
{
  paths::PathScene scene; ///< device pointers: positions, normals, triangles, face normals, materials, sky
  BvhView bvh;
  RadianceSitesView sites;
  const Index* samples = nullptr; ///< per cluster: its sample vertex
  std::uint32_t clusters = 0;
  Index vertexCount = 0;
  const Vec3f* directions = nullptr; ///< the cosine-weighted set (makeDirectionSet)
  std::uint32_t directionCount = 0;
  std::uint32_t seed = 0;
  float side = 1.f; ///< +1 the fronts, -1 the backs
  bool twoSided = false;
  float diagonal = 0.f; ///< the harmonic distance of a sample none of whose rays hit
};

/// finalGather (PhotonMapping.h) on the device: per cluster, E at its sample into
/// irradiance[j] and the harmonic mean hit distance into harmonicDistance[j]. One block
/// per cluster.
void finalGather(const GatherLaunch& g, Vec3f* irradiance, float* harmonicDistance, cudaStream_t stream);

/// E_ind of the elements of one side: out[offset + v] = interpolateVertex(...) plus, where
/// `caustics` is not null, caustics[v].
void interpolate(const Vec3f* positions, const Vec3f* normals, Index vertexCount, const Index* neighbours,
  const Index* samples, const Vec3f* irradiance, const float* harmonicDistance, const Vec3f* caustics,
  cuda::Rgba* out, cudaStream_t stream);

/// causticEstimate at every vertex into out (zero where no caustic photon is near).
void causticIrradiance(const PhotonsView& caustics, const Vec3f* positions, const Vec3f* normals,
  const Vec3f* albedo, const float* areas, Index vertexCount, std::uint32_t k, float max2, Vec3f* out,
  cudaStream_t stream);
}
