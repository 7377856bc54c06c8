#include "cuda/LightPathKernels.h"

#include "cuda/Primitives.h"
#include "shared/Bvh.h"

namespace linkgi::paths::gpu
{
namespace
{
constexpr int kThreads = cuda::kBlockThreads;

using cuda::gridBlocks;

__global__ void pathKernel(PathScene scene, BvhView bvh, Vpl* slots, Index* counts)
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
  counts[p] = Index(traceLightPath(scene, p, slots + std::size_t(p) * (scene.bounces + 1), trace));
}

__global__ void packKernel(const Vpl* slots, const Index* counts, const Offset* pathOffsets,
  std::uint32_t paths, std::uint32_t slotsPerPath, Vpl* vpls)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  const std::size_t p = i / slotsPerPath, k = i % slotsPerPath;
  if (p < paths && k < counts[p])
  {
    vpls[pathOffsets[p] + k] = slots[i];
  }
}

__global__ void subsetKernel(const Offset* pathOffsets, std::uint32_t paths, std::uint32_t subsets,
  std::uint32_t* subsetOffsets, float* subsetScale)
{
  const std::uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r > subsets)
  {
    return;
  }
  subsetOffsets[r] = std::uint32_t(pathOffsets[subsetFirstPath(r, subsets, paths)]);
  if (r < subsets)
  {
    subsetScale[r] = float(paths) / float(subsetFirstPath(r + 1, subsets, paths) - subsetFirstPath(r, subsets, paths));
  }
}
}

void traceLightPaths(const PathScene& scene, const BvhView& bvh, Vpl* slots, Index* counts,
  cudaStream_t stream)
{
  if (scene.paths == 0)
  {
    return;
  }
  pathKernel<<<(scene.paths + kThreads - 1) / kThreads, kThreads, 0, stream>>>(scene, bvh, slots, counts);
  LINKGI_CUDA_CHECK_LAUNCH("pathKernel");
}

PathScene DevicePathScene::upload(const Scene& s, const PathSetup& setup, engine::Changes changes,
  const cuda::DeviceMesh& mesh, bool passSpecular, cudaStream_t stream)
{
  using namespace engine;
  sources.upload(setup.sources, stream);
  cdf.upload(setup.cdf, stream);
  lights.upload(s.lights, stream);
  // Materials and the sky only when they changed (a light move uploads neither).
  if (changes & (kTopology | kAlbedo))
  {
    albedo.upload(s.albedo, stream);
    specular = passSpecular && s.hasSpecular();
    if (specular)
    {
      materials.upload(reinterpret_cast<const std::uint8_t*>(s.triangleMaterials.data()), s.triangles.size(), stream);
      ior.upload(s.triangleIor, stream);
    }
  }
  if (changes & (kTopology | kEmission))
  {
    emission.upload(s.emission, stream);
  }
  if (changes & (kEnvironmentLayout | kEnvironmentRadiance))
  {
    envTexels.upload(s.environment.texels, stream);
  }
  PathScene view = setup.view;
  view.positions = mesh.positions.data();
  view.normals = mesh.normals.data();
  view.albedo = albedo.data();
  view.emission = s.emission.empty() ? nullptr : emission.data();
  view.triangles = mesh.triangles.data();
  view.faceNormals = mesh.faceNormals.data();
  view.origins = mesh.origins.data();
  view.lights = lights.data();
  view.sources = sources.data();
  view.cdf = cdf.data();
  view.envTexels = s.environment.texels.empty() ? nullptr : envTexels.data();
  view.materials = specular ? materials.data() : nullptr;
  view.ior = specular && !s.triangleIor.empty() ? ior.data() : nullptr;
  return view;
}

std::size_t traceAllPaths(PathScene& view, const BvhView& bvh, std::uint32_t targetVpls, DevicePaths& paths,
  unsigned long long* pinnedFound, cudaStream_t stream)
{
  const std::uint32_t slotsPerPath = view.bounces + 1;
  std::size_t found = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    paths.slots.resize(std::size_t(view.paths) * slotsPerPath);
    paths.counts.resize(std::size_t(view.paths) + 1);
    paths.pathOffsets.resize(std::size_t(view.paths) + 1);
    LINKGI_CUDA_CHECK(cudaMemsetAsync(paths.counts.data() + view.paths, 0, sizeof(Index), stream));
    traceLightPaths(view, bvh, paths.slots.data(), paths.counts.data(), stream);
    cuda::exclusiveSum(paths.counts.data(), paths.pathOffsets.data(), std::size_t(view.paths) + 1, paths.scanTemp,
      stream);
    static_assert(sizeof(Offset) == sizeof(unsigned long long), "the VPL total lands in a ray-count slot");
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(pinnedFound, paths.pathOffsets.data() + view.paths, sizeof(Offset),
      cudaMemcpyDeviceToHost, stream));
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    found = std::size_t(*pinnedFound);
    // The same rule as the CPU's (traceVplsCpu), so both trace the same paths.
    const std::uint32_t more = pass == 0 ? secondPassPaths(view.paths, found, targetVpls, slotsPerPath) : 0;
    if (!more)
    {
      break;
    }
    view.paths = more;
  }
  return found;
}

void packVpls(const Vpl* slots, const Index* counts, const Offset* pathOffsets, std::uint32_t paths,
  std::uint32_t slotsPerPath, std::uint32_t subsets, Vpl* vpls, std::uint32_t* subsetOffsets,
  float* subsetScale, cudaStream_t stream)
{
  const std::size_t n = std::size_t(paths) * slotsPerPath;
  if (n)
  {
    packKernel<<<gridBlocks(n), kThreads, 0, stream>>>(slots, counts, pathOffsets, paths, slotsPerPath, vpls);
    LINKGI_CUDA_CHECK_LAUNCH("packKernel");
  }
  subsetKernel<<<gridBlocks(subsets + 1), kThreads, 0, stream>>>(pathOffsets, paths, subsets, subsetOffsets, subsetScale);
  LINKGI_CUDA_CHECK_LAUNCH("subsetKernel");
}
}
