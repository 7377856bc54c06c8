// Launchers of the detail nodes' kernels (DetailNodes.h): their direct light on a light
// change, and their radiance after each update of the elements' in the bounces.
#pragma once

#include "cuda/Kernels.h"
#include "shared/DetailNodes.h"

namespace linkgi::cuda
{
struct DetailParams
{
  BvhView bvh;
  const Triangle* triangles = nullptr;
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const Vec3f* faceNormals = nullptr;
  const RayOrigin* origins = nullptr;
  const DetailNode* nodes = nullptr;
  Index nodeCount = 0; ///< per side
  Index sides = 1;
};

/// nodeDirect[k] = E_d at node k (k < nodeCount: fronts, then backs) from lights[0,
/// lightCount); adds the shadow rays it traced to `rays`.
void detailDirect(const DetailParams& p, const Light* lights, Index lightCount, Vec3f* nodeDirect,
  unsigned long long* rays, cudaStream_t stream);

/// radiance[elements + k] = detailNodeRadiance of node k from the elements' radiance.
void detailRadiance(const DetailParams& p, Index elements, Index vertexCount, const Vec3f* direct,
  const Vec3f* albedo, const Vec3f* nodeDirect, Rgba* radiance, cudaStream_t stream);
}
