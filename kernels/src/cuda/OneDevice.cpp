#include "cuda/OneDevice.h"

#include "cuda/DirectLightStage.h"
#include "shared/Surface.h"

#include "cuda/Cuda.h"

#include <cmath>

namespace linkgi::cuda
{
using namespace engine;

void DeviceMesh::update(const Scene& s, Changes changes, cudaStream_t stream, SolverStats* stats)
{
  vertexCount = Index(s.vertexCount());
  triangleCount = Index(s.triangleCount());
  const bool topologyChanged = (changes & kTopology) != 0;
  const bool positionsChanged = (changes & (kTopology | kPositions)) != 0;
  const bool normalsChanged = (changes & (kTopology | kNormals)) != 0 || normals.size() != s.normals.size();
  staging.begin(PinnedStaging::room(topologyChanged ? s.triangles.size() * sizeof(Triangle) : 0) +
    2 * PinnedStaging::room(s.positions.size() * sizeof(Vec3f)));
  if (topologyChanged)
  {
    staging.upload(triangles, s.triangles, stream);
  }
  if (positionsChanged)
  {
    staging.upload(positions, s.positions, stream);
    extent = sceneExtent(s);
  }
  if (normalsChanged)
  {
    staging.upload(normals, s.normals, stream);
  }
  if (changes & kTopology)
  {
    topology.build(triangles.data(), triangleCount, vertexCount, stream);
  }
  origins.resize(vertexCount);
  faceNormals.resize(triangleCount);
  rayOrigins(positions.data(), normals.data(), topology.neighbourOffsets.data(),
    topology.neighbours.data(), vertexCount, extent.eps, origins.data(), stream);
  frontFaceNormals(positions.data(), normals.data(), triangles.data(), triangleCount,
    faceNormals.data(), stream);
  if (changes & kTopology)
  {
    bvh.build(positions.data(), vertexCount, triangles.data(), triangleCount, stream);
    if (stats)
    {
      stats->builtBvh = true;
      ++stats->bvhBuilds;
    }
  }
  else if (changes & kPositions)
  {
    bvh.refit(positions.data(), triangles.data(), stream);
    if (stats)
    {
      stats->refitBvh = true;
      ++stats->bvhRefits;
    }
  }
}

int useFirstDevice()
{
  std::string why;
  const std::vector<DeviceInfo> found = devices(&why);
  if (found.empty())
  {
    throw CudaError("No CUDA device: " + why + ".", false);
  }
  LINKGI_CUDA_CHECK(cudaSetDevice(found[0].index));
  return found[0].index;
}

DeviceContext::DeviceContext(int slots)
{
  device = useFirstDevice();
  cudaDeviceProp prop{};
  LINKGI_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  name = prop.name;
  LINKGI_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  void* pinned = nullptr;
  const cudaError_t status = cudaMallocHost(&pinned, std::size_t(slots) * sizeof(unsigned long long));
  if (status != cudaSuccess)
  {
    cudaStreamDestroy(stream);
    LINKGI_CUDA_CHECK(status);
  }
  counters = static_cast<unsigned long long*>(pinned);
}

DeviceContext::~DeviceContext()
{
  cudaFreeHost(counters);
  cudaStreamDestroy(stream);
}

void DeviceContext::describe(SolverStats& st) const
{
  st.backend = "cuda";
  st.device = name;
  st.devices = 1;
  st.linkedPerDevice.clear();
  st.batchesPerDevice.clear();
  st.msTracePerDevice.clear();
  st.msCompressPerDevice.clear();
  st.msWallPerDevice.clear();
  st.gpuBytesAllocated = MemoryLedger::takePeak();
}

void DeviceDirectLight::queue(const Scene& scene, const SolverOptions& options, const DeviceMesh& mesh,
  unsigned long long* pinnedCount, cudaStream_t stream)
{
  queueDirectLight(scene, options,
    { mesh.bvh, mesh.positions, mesh.normals, mesh.origins, mesh.topology, mesh.topology.edgeCount() },
    { lights, vertexVisible, edgeVisible, direct, counter }, stream);
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(pinnedCount, counter.data(), sizeof(unsigned long long), cudaMemcpyDeviceToHost,
    stream));
}

void DeviceFinish::run(const Scene& s, const SolverOptions& o, const DeviceMesh& mesh, const Vec3f* direct,
  const Rgba* indirect, const Vec3f* albedo, const Vec3f* emission, Solution& sol,
  std::initializer_list<Extra> extras, cudaStream_t stream)
{
  const Elements elements{ s.vertexCount(), o.twoSided };
  const std::size_t ne = elements.count();
  FinishParams f;
  f.bounce.elements = Index(ne);
  f.bounce.vertexCount = mesh.vertexCount;
  f.bounce.direct = direct;
  f.bounce.environment = indirect; // finish adds it to the bounced light: here all of E_ind
  f.bounce.albedo = albedo;
  f.bounce.emission = emission;
  f.indirect = nullptr;
  f.smoothing = smoothingOn(o);
  f.cosFeatureAngle = std::cos(o.featureAngleDegrees * (kPi / 180.f));
  f.neighbourOffsets = mesh.topology.neighbourOffsets.data();
  f.neighbours = mesh.topology.neighbours.data();
  f.normals = mesh.normals.data();
  output.resize(3 * ne);
  finish(f, output.data(), stream);
  const std::size_t bytes = ne * sizeof(Vec3f);
  // room(): a staged copy occupies a multiple of 256 bytes (a tiny mesh's 3 * bytes is less).
  std::size_t room = PinnedStaging::room(3 * bytes);
  for (const Extra& e : extras)
  {
    room += PinnedStaging::room(e.bytes);
  }
  staging.begin(room);
  const auto* at = static_cast<const unsigned char*>(staging.download(output.data(), 3 * bytes, stream));
  std::vector<const void*> staged;
  for (const Extra& e : extras)
  {
    staged.push_back(staging.download(e.from, e.bytes, stream));
  }
  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  sol.direct.resize(ne);
  sol.indirect.resize(ne);
  sol.radiance.resize(ne);
  PinnedStaging::copy(sol.direct.data(), at, bytes);
  PinnedStaging::copy(sol.indirect.data(), at + bytes, bytes);
  PinnedStaging::copy(sol.radiance.data(), at + 2 * bytes, bytes);
  std::size_t i = 0;
  for (const Extra& e : extras)
  {
    PinnedStaging::copy(e.to, staged[i++], e.bytes);
  }
}
}
