// Small scenes for the engine tests, built with MeshBuilder, and the helpers several tests
// share.
#pragma once

#include "linkgi/Error.h"
#include "scene/MeshBuilder.h"
#include "methods/reference/Reference.h"
#include "linkgi/SolverTypes.h"

#include <functional>
#include <string>

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
}
