// Decimation and the transfer of light from a proxy to its input (ProxySolver's steps).
#pragma once

#include "linkgi/Resolution.h"

namespace linkgi
{
/// Decimates `scene` (validated) to about `targetVertices` vertices with OpenMesh's Decimater:
/// quadric error as the priority, collapses that turn a face normal by more than
/// `maxNormalDeviationDegrees` or flip it refused, as are those that leave a triangle turned
/// by more than that from the input normal at one of its corners, or a sliver; boundary
/// vertices kept (so the borders of open surfaces and the creases a mesh builder splits stay
/// where they are). Below 40% of the input, a sweep over the mesh's short edges (the same
/// rules, no priorities) first takes it to 1.25 times the target, in two halves of the
/// surface on two threads; an even proxy carries the light better than the quadric's. The same input gives the same proxy on every run and machine.
/// Throws Error for a target of 0 or not smaller than the input, or where this build has no
/// OpenMesh.
/// `progress` hears ("Decimate", fraction of the collapses done) about a hundred times; when
/// it returns false the decimation stops and Aborted is thrown.
ProxyMesh decimate(const Scene& scene, std::size_t targetVertices, float maxNormalDeviationDegrees = 60.f,
  const ProgressCallback& progress = {});

/// Where each input vertex lies on the proxy: its nearest proxy triangle among those facing
/// the same way (normals within 90 degrees; the nearest of all where none does), and the
/// barycentric weights of the closest point on it.
struct ProxyTransfer
{
  std::vector<Triangle> corners;              ///< per input vertex: three proxy vertices
  std::vector<std::array<float, 3>> weights;  ///< per input vertex: their weights (sum 1)
  /// Interpolates per-proxy-vertex `values` onto the input vertices.
  std::vector<Vec3f> apply(const std::vector<Vec3f>& values) const;
};
ProxyTransfer buildTransfer(const Scene& input, const Scene& proxy);
}
