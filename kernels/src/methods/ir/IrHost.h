// Host-side set-up of instant radiosity that both backends share: the coarse visibility
// proxy. (The light paths' sources and the VPL set are shared/LightPaths.h's.)
#pragma once

#include "methods/ir/IrMath.h"

#include "linkgi/SolverTypes.h"

#include <vector>

namespace linkgi::ir
{
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
