// Where rays start: each vertex's offset follows its own edges, not the scene's size, so a
// millimetre detail in a ten-metre scene is lit as it is alone, by every method and backend.
#include "CudaFixtures.h"

#include "scene/MeshBuilder.h"
#include "shared/RayOrigin.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace linkgi;

namespace
{
const Vec3f Grey(0.6f);

/// A detail `size` wide at `at`: a finely meshed plate with a ball and a block standing on
/// it (contacts and self-shadowing), and a point light 3 sizes above, off to one side.
void addDetail(MeshBuilder& b, const Vec3f& at, float size)
{
  b.addQuadGrid(at, Vec3f(0.f, 0.f, size), Vec3f(size, 0.f, 0.f), 24, 24, Grey); // faces +y
  b.addIcosphere(at + Vec3f(0.3f, 0.2f, 0.35f) * size, 0.2f * size, 3, Grey);
  b.addBox(at + Vec3f(0.6f, 0.f, 0.55f) * size, at + Vec3f(0.8f, 0.35f, 0.75f) * size, 0.04f * size, Grey);
  Light lamp;
  lamp.position = at + Vec3f(0.1f, 3.f, 0.9f) * size;
  lamp.intensity = Vec3f(size * size); // about 0.1 W/m^2 on the plate, whatever the size
  b.scene().lights.push_back(lamp);
}

/// The detail, alone or followed by a room `scale` times its size (a floor and two walls).
Scene detailScene(float size, const Vec3f& at, float scale)
{
  MeshBuilder b;
  addDetail(b, at, size);
  if (scale > 0.f)
  {
    const float room = size * scale;
    b.addQuadGrid(Vec3f(-0.5f * room, -0.1f * room, -0.5f * room), Vec3f(0.f, 0.f, room), Vec3f(room, 0.f, 0.f), 8, 8, Grey);
    b.addQuadGrid(Vec3f(-0.5f * room, -0.1f * room, -0.5f * room), Vec3f(room, 0.f, 0.f), Vec3f(0.f, room, 0.f), 8, 8, Grey);
    b.addQuadGrid(Vec3f(-0.5f * room, -0.1f * room, -0.5f * room), Vec3f(0.f, room, 0.f), Vec3f(0.f, 0.f, room), 8, 8, Grey);
  }
  return b.take();
}

/// Area-free comparison of the detail's direct light (its vertices come first in both).
void expectDetailLitAsAlone(const Solution& inRoom, const Solution& alone, std::size_t detailVertices,
  const std::string& what)
{
  double sumRoom = 0.0, sumAlone = 0.0, largest = 0.0;
  std::size_t off = 0;
  for (std::size_t v = 0; v < detailVertices; ++v)
  {
    largest = std::max(largest, double(alone.direct[v].x));
  }
  for (std::size_t v = 0; v < detailVertices; ++v)
  {
    sumRoom += inRoom.direct[v].x;
    sumAlone += alone.direct[v].x;
    off += std::abs(inRoom.direct[v].x - alone.direct[v].x) > 0.01 * largest ? 1 : 0;
  }
  EXPECT_GT(sumAlone, 0.0) << what;
  EXPECT_NEAR(sumRoom / sumAlone, 1.0, 0.01) << what;
  // Alone, the offsets are bound by 1e-4 of the detail's own diagonal, half of the 1% of
  // an edge they are in the room: where the light grazes the ball (its terminator), the
  // one-ring samples on the chords between its vertices then see their neighbours a little
  // differently (32 of its 1,573 vertices, 2%, by more than 1% of the brightest).
  EXPECT_LE(off, 3 * detailVertices / 100) << what;
}
}

TEST(TestRayOrigins, OffsetFollowsTheVertexsEdgesWithinItsBounds)
{
  const Vec3f ring[3] = { { 1.f, 0.f, 0.f }, { 0.f, 0.5f, 0.f }, { 0.f, 0.f, 2.f } };
  const Index ids[3] = { 0, 1, 2 };
  const Vec3f origin(0.f);
  EXPECT_FLOAT_EQ(originOffset(ring, origin, ids, 3, 1.f), 0.005f); // 1% of the shortest edge
  EXPECT_FLOAT_EQ(originOffset(ring, origin, ids, 3, 1e-3f), 1e-3f); // at most the bound
  EXPECT_FLOAT_EQ(originOffset(ring, origin, ids, 0, 1e-3f), 1e-3f); // no edges: the bound
  // Far from the origin, at least kOffsetPrecision of the coordinates.
  const Vec3f far(0.f, 3e6f, 0.f);
  const Vec3f farRing[1] = { far + Vec3f(1e-3f, 0.f, 0.f) };
  EXPECT_FLOAT_EQ(originOffset(farRing, far, ids, 1, 1e3f), kOffsetPrecision * 3e6f);
}

TEST(TestRayOrigins, MillimetreDetailInATenMetreRoomIsLitAsAlone)
{
  const float size = 1e-3f;
  const Vec3f at(2.f, 0.5f, 1.5f); // off the room's centre, where coordinates are large
  const Scene alone = detailScene(size, at, 0.f), inRoom = detailScene(size, at, 1e4f);
  for (const Method method : linkgi::methods())
  {
    SolverOptions o;
    o.method = method;
    o.backend = Backend::Cpu;
    o.raysPerVertex = 64;
    o.reference.pathsPerVertex = 64;
    Solver a, b;
    const Solution& lone = a.update(alone, o);
    const Solution& room = b.update(inRoom, o);
    expectDetailLitAsAlone(room, lone, alone.vertexCount(), "method " + std::to_string(int(method)));
  }
}

TEST(TestRayOrigins, MillimetreDetailInATenMetreRoomIsLitAsAloneOnTheGpu)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const float size = 1e-3f;
  const Vec3f at(2.f, 0.5f, 1.5f);
  const Scene alone = detailScene(size, at, 0.f), inRoom = detailScene(size, at, 1e4f);
  for (const Method method : { Method::Links, Method::InstantRadiosity, Method::ImplicitVisibility,
         Method::PhotonMapping })
  {
    SolverOptions o;
    o.method = method;
    o.raysPerVertex = 64;
    Solver cpu, gpu;
    const Solution& lone = cpu.update(alone, test::onBackend(Backend::Cpu, o));
    const Solution& room = gpu.update(inRoom, test::onBackend(Backend::Cuda, o));
    ASSERT_EQ(gpu.stats().backend, "cuda") << gpu.stats().backendNote;
    expectDetailLitAsAlone(room, lone, alone.vertexCount(), "cuda method " + std::to_string(int(method)));
  }
}
