#include "ir/IrKernels.h"

#include "linkgi/Bvh.h"

namespace linkgi::ir::gpu
{
namespace
{
constexpr int kThreads = 128;

__global__ void pathKernel(PathScene scene, BvhView bvh, Vpl* slots, int* counts)
{
  const std::uint32_t p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= scene.paths)
  {
    return;
  }
  const auto trace = [&bvh](const Ray& ray) {
    Hit h;
    bvh::traverse<false>(bvh, ray, h);
    return h;
  };
  counts[p] = traceLightPath(scene, p, slots + std::size_t(p) * (scene.bounces + 1), trace);
}

__global__ void gatherKernel(GatherLaunch p, cuda::Rgba* out, unsigned long long* rays)
{
  const Index elements = p.twoSided ? 2 * p.vertexCount : p.vertexCount;
  const Index e = blockIdx.x * blockDim.x + threadIdx.x;
  if (e >= elements)
  {
    return;
  }
  const Index v = e < p.vertexCount ? e : e - p.vertexCount;
  const float sign = e < p.vertexCount ? 1.f : -1.f;
  const GatherParams& gp = p.params;
  const Vec3f n = p.normals[v] * sign;
  const Vec3f x = p.positions[v] + p.shifts[v];
  const Vec3f origin = vertexLightOrigin(p.positions[v], p.normals[v], p.shifts[v], sign, gp.eps);
  const std::uint32_t r = vertexSubset(v, gp.subsets, gp.seed);
  // As gatherCpu sums: the VPLs too close for the proxy to tell, then the visible ones.
  Vec3f near(0.f), far(0.f);
  unsigned long long traced = 0;
  for (std::uint32_t k = p.subsetOffsets[r]; k < p.subsetOffsets[r + 1]; ++k)
  {
    Ray ray;
    const Vec3f ek = vplIrradiance(p.vpls[k], x, origin, n, gp.dmin, gp.eps, ray);
    if (!(maxComponent(ek) > 0.f))
    {
      continue;
    }
    if (gp.proxyMargin > 0.f && !proxyShadowRay(ray, gp.proxyMargin))
    {
      near += ek;
      continue;
    }
    ++traced;
    Hit h;
    if (!bvh::traverse<true>(p.visibility, ray, h))
    {
      far += ek;
    }
  }
  const Vec3f sum = (near + far) * p.subsetScale[r];
  out[e] = { sum.x, sum.y, sum.z, 0.f };
  atomicAdd(rays, traced);
}
}

void traceLightPaths(const PathScene& scene, const BvhView& bvh, Vpl* slots, int* counts,
  cudaStream_t stream)
{
  if (scene.paths == 0)
  {
    return;
  }
  pathKernel<<<(scene.paths + kThreads - 1) / kThreads, kThreads, 0, stream>>>(scene, bvh, slots, counts);
  LINKGI_CUDA_CHECK_LAUNCH("pathKernel");
}

void gatherVpls(const GatherLaunch& p, cuda::Rgba* out, unsigned long long* rays, cudaStream_t stream)
{
  const std::size_t elements = p.twoSided ? 2 * std::size_t(p.vertexCount) : p.vertexCount;
  if (elements == 0)
  {
    return;
  }
  gatherKernel<<<unsigned((elements + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, out, rays);
  LINKGI_CUDA_CHECK_LAUNCH("gatherKernel");
}
}
