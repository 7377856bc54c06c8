#include "cuda/DirectLightStage.h"

#include "shared/Surface.h"

#include <algorithm>

namespace linkgi::cuda
{
void queueDirectLight(const Scene& s, const SolverOptions& options, const DirectLightMesh& mesh,
  const DirectLightBuffers& out, cudaStream_t stream)
{
  const Index nv = Index(s.vertexCount());
  const Elements elements{ s.vertexCount(), options.twoSided };
  std::vector<Light> lit;
  for (const Light& light : s.lights)
  {
    if (maxComponent(light.intensity) > 0.f)
    {
      lit.push_back(light);
    }
  }
  out.direct.resize(elements.count());
  out.direct.fillZero(stream);
  out.lights.upload(lit, stream);
  out.vertexVisible.resize(std::max<std::size_t>(1, lit.size() * nv));
  out.edgeVisible.resize(std::max<std::size_t>(1, lit.size() * mesh.edgeCount));
  out.counter.resize(1);
  out.counter.fillZero(stream);
  DirectLightParams p;
  p.bvh = mesh.bvh.view();
  p.positions = mesh.positions.data();
  p.normals = mesh.normals.data();
  p.origins = mesh.origins.data();
  p.edges = mesh.topology.edges.data();
  p.neighbourOffsets = mesh.topology.neighbourOffsets.data();
  p.vertexEdges = mesh.topology.vertexEdges.data();
  p.vertexCount = nv;
  p.edgeCount = mesh.edgeCount;
  p.oversampling = options.lightOversampling;
  for (int side = 0; side < (options.twoSided ? 2 : 1); ++side)
  {
    addDirectLights(p, out.lights.data(), int(lit.size()), side == 0 ? 1.f : -1.f, side == 0 ? 0 : nv,
      out.vertexVisible.data(), out.edgeVisible.data(), out.direct.data(), out.counter.data(), stream);
  }
}
}
