#include "cuda/DeviceMesh.h"

#include "linkgi/Cuda.h"

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
    extent = ir::sceneExtent(s);
  }
  if (normalsChanged)
  {
    staging.upload(normals, s.normals, stream);
  }
  if (changes & kTopology)
  {
    topology.build(triangles.data(), triangleCount, vertexCount, stream);
  }
  shifts.resize(vertexCount);
  faceNormals.resize(triangleCount);
  originShifts(positions.data(), normals.data(), topology.neighbourOffsets.data(),
    topology.neighbours.data(), vertexCount, shifts.data(), stream);
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
}
