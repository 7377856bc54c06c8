// Host-side set-up of instant radiosity that both backends share: the table of light-path
// sources, the coarse visibility proxy, and the per-subset layout of the VPL set.
#pragma once

#include "methods/ir/IrMath.h"

#include "linkgi/SolverTypes.h"

#include <vector>

namespace linkgi::ir
{
/// The sources a light path starts from, picked in proportion to their power, and the
/// PathScene over host arrays (a GPU backend swaps in its device pointers).
struct PathSetup
{
  std::vector<Source> sources;
  std::vector<float> cdf;
  PathScene view;
  /// Surface VPLs closer than 0.8 * dmin to a vertex give it nothing (distanceBound).
  float dmin = 0.f;
  /// The VPLs asked for (InstantRadiosityOptions::vplCount).
  std::uint32_t targetVpls = 1;
};

/// ceil(vplCount / bounces) paths (vplCount with no bounces): about vplCount VPLs where
/// every path stays in the scene.
std::uint32_t pathCount(const SolverOptions& options);

/// Paths for a second pass when the first pass of `paths` left `found` VPLs, fewer than half
/// the `target` (in an open scene most paths leave it): enough for about `target` at the
/// rate seen, at most 64 times the first pass and 2^22 VPL slots; 0 to keep the first pass.
/// Both backends ask it, so they trace the same paths.
std::uint32_t secondPassPaths(std::uint32_t paths, std::size_t found, std::uint32_t target,
  std::uint32_t slotsPerPath);

/// Sources of `scene` (validated) and the view over its arrays and `faceNormals`
/// (frontFaceNormals). Lights start paths only when bounces > 0 (their direct light is the
/// light-link stage's). A scene with no source gets an empty table and no VPLs. `extent`:
/// sceneExtent(scene) where the caller kept it (computed here otherwise).
PathSetup buildPathSetup(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const SolverOptions& options, const SceneExtent* extent = nullptr);

/// A VPL set: VPLs of subset r are [subsetOffsets[r], subsetOffsets[r + 1]), each subset a
/// contiguous run of light paths (a run of the Halton sequence is itself well spread),
/// scaled by subsetScale[r] = paths / paths in subset r when a vertex gathers only it.
struct VplSet
{
  std::vector<Vpl> vpls;
  std::vector<std::uint32_t> subsetOffsets;
  std::vector<float> subsetScale;
  std::size_t count() const { return vpls.size(); }
};

/// First path of subset r of `subsets` over `paths` paths.
LINKGI_HOST_DEVICE inline std::uint32_t subsetFirstPath(std::uint32_t r, std::uint32_t subsets, std::uint32_t paths)
{
  return std::uint32_t(std::uint64_t(r) * paths / subsets);
}

/// Packs per-path VPL slots (bounces + 1 per path, counts[i] used) into a VplSet.
VplSet packVpls(const std::vector<Vpl>& slots, const std::vector<int>& counts,
  std::uint32_t slotsPerPath, std::uint32_t subsets);

/// A coarse stand-in of the mesh for imperfect visibility: vertices clustered on a grid of
/// `resolution` cells along the box's longest axis (each cluster at its mean), triangles
/// whose corners fall into three different cells. Shadow rays against it skip `margin` at
/// both ends (proxyShadowRay), where the proxy passes near the surface it stands for.
struct Proxy
{
  std::vector<Vec3f> positions;
  std::vector<Triangle> triangles;
  float margin = 0.f;
};
Proxy buildProxy(const Scene& scene, std::uint32_t resolution);

/// The proxy's grid: `resolution` cells of `cell` along the box's longest axis from `lo`;
/// cells are numbered in (resolution + 1)^3 (a vertex on the far face gets the extra cell).
/// One copy for the host's buildProxy and the GPU's (ir/IrKernels.h).
struct ProxyGrid
{
  Vec3f lo;
  float cell = 1.f;
  std::uint32_t resolution = 1;
  LINKGI_HOST_DEVICE std::uint64_t cellOf(const Vec3f& p) const
  {
    const std::uint64_t n = resolution + 1;
    return (axis(p.x, lo.x) * n + axis(p.y, lo.y)) * n + axis(p.z, lo.z);
  }
  /// The bits cellOf's numbers take.
  int cellBits() const
  {
    const std::uint64_t cells = std::uint64_t(resolution + 1) * (resolution + 1) * (resolution + 1);
    int bits = 1;
    while (bits < 64 && (std::uint64_t(1) << bits) < cells)
    {
      ++bits;
    }
    return bits;
  }
  /// Shadow rays against the proxy skip this much at both ends (proxyShadowRay).
  float margin() const { return 1.5f * cell; }

private:
  LINKGI_HOST_DEVICE std::uint64_t axis(float x, float l) const
  {
    const float c = (x - l) / cell;
    return std::uint64_t(c < float(resolution) ? c : float(resolution));
  }
};
ProxyGrid proxyGrid(const SceneExtent& extent, std::uint32_t resolution);
}
