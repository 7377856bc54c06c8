// The direct-light (light-link) stage on one GPU, as every method's CUDA backend queues it;
// the CPU's is computeDirectLight (DirectLight.h).
#pragma once

#include "cuda/DeviceBvh.h"
#include "cuda/DeviceTopology.h"
#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"

#include "linkgi/SolverTypes.h"

namespace linkgi::cuda
{
/// What the shadow rays read: a mesh already on the GPU.
struct DirectLightMesh
{
  const DeviceBvh& bvh;
  const GPUBuffer<Vec3f>& positions;
  const GPUBuffer<Vec3f>& normals;
  const GPUBuffer<RayOrigin>& origins; ///< where each vertex's rays start
  const DeviceTopology& topology;
  Index edgeCount; ///< the topology's, read once it is valid on the host
};

/// The backend's buffers the stage fills; kept between updates so equal sizes allocate nothing.
struct DirectLightBuffers
{
  GPUBuffer<Light>& lights;          ///< the lights that emit
  GPUBuffer<float>& vertexVisible;   ///< scratch: lights x vertices
  GPUBuffer<float>& edgeVisible;     ///< scratch: lights x edges
  GPUBuffer<Vec3f>& direct;          ///< E_d per element (both sides when two-sided)
  GPUBuffer<unsigned long long>& counter; ///< [0]: shadow rays traced
};

/// Queues E_d of the scene's lights on every element on `stream`, and does not wait: a light
/// with no intensity traces nothing (as on the CPU), `direct` and the ray counter start at 0.
void queueDirectLight(const Scene& scene, const SolverOptions& options, const DirectLightMesh& mesh,
  const DirectLightBuffers& out, cudaStream_t stream);
}
