// Light links on the GPU: one any-hit shadow ray per lit vertex and per edge midpoint of a
// lit vertex (the 1:4 subdivision points), then the hat-weighted visibility per vertex.
#include "cuda/Kernels.h"

#include "shared/DirectLight.h"

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;

__device__ inline bool lit(const DirectLightParams& p, const Light& light, Index v, float sign, Vec3f& e)
{
  Vec3f toLight;
  e = unshadowedIrradiance(light, p.positions[v], p.normals[v] * sign, toLight);
  return maxComponent(e) > 0.f;
}

__device__ inline float visibility(const BvhView& bvh, const Light& light, const Vec3f& origin)
{
  Hit h;
  return bvh::traverse<true>(bvh, shadowRay(light, origin, directionToLight(light, origin)), h) ? 0.f : 1.f;
}

/// Samples [0, vertexCount) are vertices, the rest edge midpoints; blockIdx.y is the light.
__global__ void shadowSamplesKernel(DirectLightParams p, const Light* lights, float sign,
  float* vertexVisible, float* edgeVisible, unsigned long long* rays)
{
  const Index s = blockIdx.x * blockDim.x + threadIdx.x;
  const Light light = lights[blockIdx.y];
  vertexVisible += std::size_t(blockIdx.y) * p.vertexCount;
  edgeVisible += std::size_t(blockIdx.y) * p.edgeCount;
  const Index total = p.vertexCount + (p.oversampling ? p.edgeCount : 0);
  bool traced = false;
  if (s < p.vertexCount)
  {
    Vec3f e;
    float visible = 0.f;
    if (lit(p, light, s, sign, e))
    {
      visible = visibility(p.bvh, light,
        vertexLightOrigin(p.positions[s], p.normals[s], p.origins[s], sign));
      traced = true;
    }
    vertexVisible[s] = visible;
  }
  else if (s < total)
  {
    const Index edge = s - p.vertexCount;
    const Index a = p.edges[2 * edge], b = p.edges[2 * edge + 1];
    Vec3f ea, eb;
    float visible = 0.f;
    if (lit(p, light, a, sign, ea) | lit(p, light, b, sign, eb))
    {
      visible = visibility(p.bvh, light, edgeLightOrigin(p.positions[a], p.positions[b],
        p.normals[a], p.normals[b], p.origins[a], p.origins[b], sign));
      traced = true;
    }
    edgeVisible[edge] = visible;
  }
  const unsigned ballot = __ballot_sync(0xffffffffu, traced);
  if ((threadIdx.x & 31) == 0 && ballot)
  {
    atomicAdd(rays, static_cast<unsigned long long>(__popc(ballot)));
  }
}

/// Per vertex, the lights in order (the CPU's order of additions).
__global__ void combineKernel(DirectLightParams p, const Light* lights, int lightCount, float sign,
  Index sideOffset, const float* vertexVisible, const float* edgeVisible, Vec3f* irradiance)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v >= p.vertexCount)
  {
    return;
  }
  Vec3f sum = irradiance[v + sideOffset];
  for (int l = 0; l < lightCount; ++l)
  {
    Vec3f e;
    if (lit(p, lights[l], v, sign, e))
    {
      sum += e * oversampledVisibility(v, vertexVisible + std::size_t(l) * p.vertexCount,
        edgeVisible + std::size_t(l) * p.edgeCount, p.neighbourOffsets, p.vertexEdges, p.oversampling);
    }
  }
  irradiance[v + sideOffset] = sum;
}
}

void addDirectLights(const DirectLightParams& p, const Light* lights, int lightCount, float sign,
  Index sideOffset, float* vertexVisible, float* edgeVisible, Vec3f* irradiance,
  unsigned long long* rays, cudaStream_t stream)
{
  const Index samples = p.vertexCount + (p.oversampling ? p.edgeCount : 0);
  if (samples == 0 || lightCount == 0)
  {
    return;
  }
  const dim3 grid((samples + kThreads - 1) / kThreads, unsigned(lightCount));
  shadowSamplesKernel<<<grid, kThreads, 0, stream>>>(p, lights, sign, vertexVisible, edgeVisible, rays);
  LINKGI_CUDA_CHECK_LAUNCH("shadowSamplesKernel");
  combineKernel<<<(p.vertexCount + kThreads - 1) / kThreads, kThreads, 0, stream>>>(
    p, lights, lightCount, sign, sideOffset, vertexVisible, edgeVisible, irradiance);
  LINKGI_CUDA_CHECK_LAUNCH("combineKernel");
}
}
