// Inputs at the edges, each given to a solver that holds a solution: the error
// names the problem AND the previous solution stays bitwise as it was (TestBadInput checks
// the messages on fresh solvers; TestFaults the aborts; TestCudaFallback the GPU's faults).
#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <limits>

using namespace linkgi;
using test::quickOptions;

namespace
{
struct Case
{
  const char* words; ///< in the error's message
  std::function<void(Scene&, SolverOptions&)> spoil;
};
}

TEST(EdgeInputs, EveryRejectedInputNamesItsProblemAndKeepsThePreviousSolution)
{
  constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  constexpr float inf = std::numeric_limits<float>::infinity();
  const Case cases[] = {
    { "no vertices", [](Scene& s, SolverOptions&) { s = Scene{}; } },
    { "no triangles", [](Scene& s, SolverOptions&) { s.triangles.clear(); } },
    { "Vertex 5 has a non-finite (NaN or Inf) position", [&](Scene& s, SolverOptions&) { s.positions[5].y = nan; } },
    { "Vertex 5 has a non-finite (NaN or Inf) position", [&](Scene& s, SolverOptions&) { s.positions[5].y = inf; } },
    { "normal", [&](Scene& s, SolverOptions&) { s.normals[2].x = inf; } },
    { "Light 0", [&](Scene& s, SolverOptions&) { s.lights[0].position.z = nan; } },
    { "degenerate", [](Scene& s, SolverOptions&) {
       for (Triangle& t : s.triangles)
       {
         t.v[2] = t.v[1]; // every triangle degenerate: nothing left
       }
     } },
    { "albedo above 1", [](Scene& s, SolverOptions& o) {
       s.albedo[0] = Vec3f(1.5f);
       o.albedoPolicy = AlbedoPolicy::Reject;
     } },
    { "perfect square", [](Scene&, SolverOptions& o) { o.raysPerVertex = 200; } },
    // Ray origins Embree rejects (its `ray.valid()`, beyond ~1.8e18): a light far out, which
    // the SolverOptions fuzz target reached (Testing/Data/fuzz/SolverOptions/embree-ray-valid),
    // and a room-sized scene far from the origin.
    { "Light 0 is more than 2^60", [](Scene& s, SolverOptions&) { s.lights[0].position.x = 1e19f; } },
    { "more than 2^60 scene units", [](Scene& s, SolverOptions&) {
       for (Vec3f& p : s.positions)
       {
         p.x += 1e20f;
       }
     } },
  };
  const Scene good = test::roomWithBlock();
  // Every method holds its previous solution the same way (validation comes before any stage).
  for (const Method method : linkgi::methods())
  {
    SCOPED_TRACE(::testing::Message() << "method " << int(method));
    const auto options = [method]() {
      SolverOptions o = quickOptions();
      o.method = method;
      o.photonMapping.photons = 16384;
      o.photonMapping.gatherRays = 64;
      o.reference.pathsPerVertex = 16;
      return o;
    };
    Solver solver;
    const Solution before = solver.update(good, options());
    for (const Case& c : cases)
    {
      SCOPED_TRACE(c.words);
      Scene s = good;
      SolverOptions o = options();
      c.spoil(s, o);
      try
      {
        solver.update(s, o);
        ADD_FAILURE() << "no error";
      }
      catch (const Error& e)
      {
        EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << e.what();
      }
      const Solution& after = solver.solution();
      ASSERT_EQ(after.elementCount(), before.elementCount());
      EXPECT_EQ(std::memcmp(after.radiance.data(), before.radiance.data(), before.radiance.size() * sizeof(Vec3f)), 0);
      EXPECT_EQ(std::memcmp(after.direct.data(), before.direct.data(), before.direct.size() * sizeof(Vec3f)), 0);
    }
    // And the solver still works: the good scene again gives the same bits.
    const Solution& again = solver.update(good, options());
    EXPECT_EQ(std::memcmp(again.radiance.data(), before.radiance.data(), before.radiance.size() * sizeof(Vec3f)), 0);
  }
}
