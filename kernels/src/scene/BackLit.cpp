#include "scene/BackLit.h"

#include "shared/DirectLight.h"

#include <algorithm>

namespace linkgi
{
LitOnTheirBacks litOnlyOnTheirBacks(const Scene& scene, const std::vector<Index>& surfaceOf, std::size_t surfaces,
  const std::vector<Vec3f>& direct, const RayTracer& tracer)
{
  const std::size_t nv = std::min({ scene.vertexCount(), direct.size(), surfaceOf.size() });
  std::vector<std::uint8_t> front(surfaces, 0);
  for (std::size_t v = 0; v < nv; ++v)
  {
    front[surfaceOf[v]] |= maxComponent(direct[v]) > 0.f ? 1 : 0;
  }
  // Up to kBackRays back shadow rays per surface without front light, from the centres of
  // its triangles in order (every triangle of a small surface, the first ones of a large
  // one), and at most kBackSamples in all (a triangle soup is as many surfaces as
  // triangles): the surfaces past those are left unknown. From a triangle's centre, not a
  // vertex: a vertex on a sharp edge (each face of a cube is a surface of its own) lies in
  // the planes of its neighbours, and a ray from just behind it slips out along the edge.
  const float offset = 1e-4f * boundingDiagonal(scene.positions); // one for all: a check, not the light
  std::vector<int> cast(surfaces, 0);
  std::vector<Ray> rays;
  std::vector<Index> rayOf;
  for (const Triangle& t : scene.triangles)
  {
    if (rays.size() >= kBackSamples)
    {
      break;
    }
    if (t.v[0] >= nv || t.v[1] >= nv || t.v[2] >= nv)
    {
      continue;
    }
    const Index k = surfaceOf[t.v[0]];
    if (front[k] || cast[k] >= kBackRays)
    {
      continue;
    }
    const Vec3f a = scene.positions[t.v[0]], b = scene.positions[t.v[1]], c = scene.positions[t.v[2]];
    const Vec3f p = (a + b + c) * (1.f / 3.f);
    Vec3f back = cross(b - a, c - a);
    const Vec3f normals = scene.normals[t.v[0]] + scene.normals[t.v[1]] + scene.normals[t.v[2]];
    if (dot(back, back) == 0.f)
    {
      continue;
    }
    back = normalize(dot(back, normals) < 0.f ? back : -back); // away from the normals' side
    for (const Light& light : scene.lights)
    {
      Vec3f toLight;
      if (maxComponent(unshadowedIrradiance(light, p, back, toLight)) > 0.f)
      {
        const Vec3f origin = p + back * offset;
        rays.push_back(shadowRay(light, origin, directionToLight(light, origin)));
        rayOf.push_back(k);
        ++cast[k];
        break;
      }
    }
  }
  std::vector<std::uint8_t> blocked(rays.size());
  tracer.occluded(rays.data(), blocked.data(), rays.size());
  std::vector<int> reached(surfaces, 0);
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    reached[rayOf[i]] += blocked[i] ? 0 : 1;
  }
  LitOnTheirBacks r;
  std::vector<std::uint8_t> flagged(surfaces, 0), known(surfaces, 0);
  for (std::size_t k = 0; k < surfaces; ++k)
  {
    r.frontLit += front[k];
    flagged[k] = cast[k] > 0 && 2 * reached[k] >= cast[k] ? 1 : 0;
    known[k] = front[k] || cast[k] > 0 || rays.size() < kBackSamples ? 1 : 0;
    r.surfaces += flagged[k];
  }
  for (const Triangle& t : scene.triangles)
  {
    const Index k = t.v[0] < surfaceOf.size() ? surfaceOf[t.v[0]] : kInvalidIndex;
    r.triangles += k != kInvalidIndex && flagged[k] ? 1 : 0;
    r.knownTriangles += k != kInvalidIndex && known[k] ? 1 : 0;
  }
  return r;
}
}
