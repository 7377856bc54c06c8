#include "shared/Surface.h"

#include "cpu/Parallel.h"

namespace linkgi
{
std::vector<Vec3f> environmentTexelRadiance(const Environment& env)
{
  if (!env.hasTexture())
  {
    return { env.color };
  }
  std::vector<Vec3f> radiance(env.texels.size());
  for (std::size_t i = 0; i < radiance.size(); ++i)
  {
    radiance[i] = env.color * env.texels[i];
  }
  return radiance;
}

std::vector<Vec3f> frontFaceNormals(const Scene& scene)
{
  std::vector<Vec3f> normals(scene.triangleCount());
  parallelRanges(normals.size(), 8192, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      normals[t] = frontFaceNormal(scene.positions.data(), scene.normals.data(), scene.triangles[t]);
    }
  });
  return normals;
}
}
