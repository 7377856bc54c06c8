// The geometry the link rays need, derived on the GPU: the one-ring topology (in
// Topology::build's order), the ray-origin shifts and the front-face normals. Host-facing:
// no device code.
#pragma once

#include "cuda/GPUBuffer.h"

#include "shared/RayOrigin.h"
#include "linkgi/Scene.h"

namespace linkgi::cuda
{
class DeviceTopology
{
public:
  DeviceTopology();
  ~DeviceTopology();
  DeviceTopology(const DeviceTopology&) = delete;
  DeviceTopology& operator=(const DeviceTopology&) = delete;

  /// Topology::build on the GPU: neighbours ascending per vertex, edges (a < b) in (a, b)
  /// order, each neighbour's edge. Sort of the triangles' directed vertex pairs, unique, two
  /// scans; no host round trip (edgeCount() is valid once `stream` has got there).
  void build(const Triangle* triangles, Index triangleCount, Index vertexCount, cudaStream_t stream);
  /// Edges of the last build; read after synchronising the build's stream.
  Index edgeCount() const { return Index(counts[1]); }

  GPUBuffer<Index> neighbourOffsets, neighbours, edges, vertexEdges;

private:
  // Scratch, kept for the next build: directed pairs, sorted / unique pairs, head flags
  // and their scan.
  GPUBuffer<std::uint64_t> pairs, sorted;
  GPUBuffer<Index> flags;
  GPUBuffer<Offset> scan, deviceCounts;
  GPUBuffer<unsigned char> temp;
  Offset* counts = nullptr; ///< pinned: neighbour entries, edges
};

/// origins[v] = rayOrigin(...) over v's ring with `bound` = rayEpsilon (RayOrigin.h), as
/// the CPU computes it.
void rayOrigins(const Vec3f* positions, const Vec3f* normals, const Index* neighbourOffsets,
  const Index* neighbours, Index vertexCount, float bound, RayOrigin* origins, cudaStream_t stream);
/// out[t] = frontFaceNormal(...) (Links.h).
void frontFaceNormals(const Vec3f* positions, const Vec3f* normals, const Triangle* triangles,
  Index triangleCount, Vec3f* out, cudaStream_t stream);
}
