#include "shared/RayOrigin.h"

#include "cpu/Parallel.h"

namespace linkgi
{
float rayEpsilon(const Scene& scene)
{
  return rayEpsilon(boundingDiagonal(scene.positions));
}

std::vector<RayOrigin> rayOrigins(const Scene& scene, const Topology& topology)
{
  const float bound = rayEpsilon(scene);
  std::vector<RayOrigin> origins(scene.vertexCount());
  parallelRanges(origins.size(), 4096, [&](std::size_t first, std::size_t last) {
    for (std::size_t v = first; v < last; ++v)
    {
      const Index begin = topology.neighbourOffsets[v], end = topology.neighbourOffsets[v + 1];
      origins[v] = rayOrigin(scene.positions.data(), scene.positions[v], scene.normals[v],
        topology.neighbours.data() + begin, end - begin, bound);
    }
  });
  return origins;
}

SceneExtent sceneExtent(const Scene& s)
{
  SceneExtent e;
  positionBounds(s.positions, e.lo, e.hi); // one pass: a deformation's geometry stage waits for it
  e.diagonal = boxDiagonal(e.lo, e.hi);
  e.eps = rayEpsilon(e.diagonal);
  return e;
}
}
