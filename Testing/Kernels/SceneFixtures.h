// Small scenes for the engine tests, built with MeshBuilder, and the helpers several tests
// share.
#pragma once

#include "linkgi/Error.h"
#include "scene/MeshBuilder.h"
#include "methods/reference/Reference.h"
#include "linkgi/SolverTypes.h"
#include "shared/Metrics.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace linkgi::test
{
/// Default options with 16 rays per vertex: quick solves for tests of behaviour, not accuracy.
inline SolverOptions quickOptions()
{
  SolverOptions o;
  o.raysPerVertex = 16;
  return o;
}

/// The message of the linkgi::Error that `f` throws, or "" when it throws none.
inline std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}

/// Two unit squares, n x n cells each: `emitter` (Le = 1, rho = 0) and `receiver` (rho = 0).
/// Parallel: facing each other at unit distance. Perpendicular: sharing an edge.
/// Vertices [0, (n+1)^2) are the emitter, the rest the receiver.
inline Scene twoSquares(bool perpendicular, int n)
{
  MeshBuilder b;
  b.addQuadGrid({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, n, n, Vec3f(0.f), Vec3f(1.f)); // faces +z
  if (perpendicular)
  {
    b.addQuadGrid({ 0, 0, 0 }, { 0, 0, 1 }, { 1, 0, 0 }, n, n, Vec3f(0.f)); // y = 0, faces +y
  }
  else
  {
    b.addQuadGrid({ 0, 0, 1 }, { 0, 1, 0 }, { 1, 0, 0 }, n, n, Vec3f(0.f)); // z = 1, faces -z
  }
  return b.take();
}

/// A closed room (inward box) with a block on the floor and a point light under the ceiling:
/// a quick scene with shadows, colour bleeding and every stage of the solver.
/// E_d + E_ind of the path-traced reference: `paths` per vertex, `bounces` bounces.
inline std::vector<Vec3f> referenceTotal(const Scene& scene, std::uint32_t paths, std::uint32_t bounces)
{
  ReferenceOptions ro;
  ro.pathsPerVertex = paths;
  ro.bounces = bounces;
  const ReferenceSolution ref = solveReference(scene, ro);
  std::vector<Vec3f> total(ref.direct.size());
  for (std::size_t i = 0; i < total.size(); ++i)
  {
    total[i] = ref.direct[i] + ref.indirect[i];
  }
  return total;
}

inline Scene roomWithBlock(float cell = 0.25f)
{
  MeshBuilder b;
  b.addBox({ -2, 0, -2 }, { 2, 3, 2 }, cell, Vec3f(0.7f, 0.6f, 0.5f), true);
  b.addBox({ -0.5f, 0, -0.5f }, { 0.5f, 1, 0.5f }, cell, Vec3f(0.2f, 0.7f, 0.3f));
  Scene s = b.take();
  Light l;
  l.position = { 0.3f, 2.5f, 0.4f };
  l.intensity = { 10.f, 9.f, 8.f };
  s.lights.push_back(l);
  return s;
}

/// A slab (1.2 x 0.2 x 1.2 m, cells of 0.1 m) resting 2 mm over the floor of a lit room
/// (4 x 3 x 4 m, cells of 0.25 m): its underside sees only the floor under it, which no
/// light reaches but through the gap, and whose triangles' corners lie out in the light.
/// The slab's vertices are [slabBegin, vertexCount()).
inline Scene slabOnTheFloor(Index& slabBegin)
{
  MeshBuilder b;
  b.addBox({ -2, 0, -2 }, { 2, 3, 2 }, 0.25f, Vec3f(0.6f), true);
  slabBegin = b.vertexCount();
  b.addBox({ -0.6f, 0.002f, -0.6f }, { 0.6f, 0.2f, 0.6f }, 0.1f, Vec3f(0.6f));
  Scene s = b.take();
  Light l;
  l.position = { 0.9f, 2.7f, 0.4f };
  l.intensity = Vec3f(10.f);
  s.lights.push_back(l);
  return s;
}

/// A plate 10 cm high (4 x 4 cells, facing +x) stands on a 4 x 4 m floor of two triangles in
/// a spot light's pool 0.9 m wide: the floor's corners lie outside the cone, so their direct
/// light is 0, but the floor around the plate is lit. The plate's vertices are
/// [plateBegin, vertexCount()).
inline Scene plateInAPoolOfLight(Index& plateBegin)
{
  MeshBuilder b;
  b.addQuadGrid({ -2, 0, -2 }, { 0, 0, 4 }, { 4, 0, 0 }, 1, 1, Vec3f(0.5f)); // faces +y
  plateBegin = b.addQuadGrid({ 0, 0, -0.05f }, { 0, 0.1f, 0 }, { 0, 0, 0.1f }, 4, 4, Vec3f(0.5f));
  Scene s = b.take();
  Light l;
  l.type = LightType::Spot;
  l.position = { 0.3f, 1.f, 0.f };
  l.direction = { 0.f, -1.f, 0.f };
  l.coneAngleDegrees = 25.f;
  l.intensity = Vec3f(1.f);
  s.lights.push_back(l);
  return s;
}

/// The mean indirect light (red) over vertices [begin, vertexCount()) of a one-bounce
/// solution of `s`, and the path tracer's there (4096 paths per vertex, one bounce).
inline std::pair<double, double> meanIndirectAndReference(const Scene& s, const std::vector<Vec3f>& indirect, Index begin)
{
  ReferenceOptions ro;
  ro.pathsPerVertex = 4096;
  ro.bounces = 1;
  const ReferenceSolution ref = solveReference(s, ro);
  double sum = 0.0, reference = 0.0;
  for (std::size_t v = begin; v < s.vertexCount(); ++v)
  {
    sum += indirect[v].x;
    reference += ref.indirect[v].x;
  }
  const double n = double(s.vertexCount() - begin);
  return { sum / n, reference / n };
}

/// The area-weighted mean luminance of e over the vertices [begin, end) whose normals point
/// up (facing > 0: y above 0.9), down (facing < 0: y below -0.9) or anywhere (facing 0).
inline double meanLuminance(const Scene& s, const std::vector<Vec3f>& e, Index begin, Index end, int facing)
{
  const std::vector<float> area = vertexAreas(s);
  double sum = 0, weight = 0;
  for (Index v = begin; v < end; ++v)
  {
    if (facing == 0 || (facing > 0 ? s.normals[v].y > 0.9f : s.normals[v].y < -0.9f))
    {
      sum += area[v] * luminance(e[v]);
      weight += area[v];
    }
  }
  return sum / weight;
}
}
