// libFuzzer target: the solver's options, every field any value (the methods' own options
// included), on a small box or on any scene that validation accepts. validateOptions either
// throws linkgi::Error or the update succeeds, with one finite, non-negative value per
// element; and a second update with other options, reusing the first one's caches, gives
// bitwise what a fresh solver gives.
#include "FuzzInput.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <cmath>
#include <cstdlib>

using namespace linkgi;

namespace
{
SolverOptions options(linkgi_fuzz::Input& in)
{
  SolverOptions o;
  o.method = Method(in.count(7)); // past the last method: an error naming it
  // Perfect squares mostly (others are errors); at most 32 x 32 rays and 64 bounces are
  // solved: the cost grows with both, larger counts are slow, not different.
  const std::uint32_t k = std::uint32_t(in.count(32));
  o.raysPerVertex = in.count(7) ? k * k : in.integer<std::uint32_t>();
  o.bounces = in.count(7) ? std::uint32_t(in.count(64)) : in.integer<std::uint32_t>();
  o.smoothing = in.boolean();
  o.featureAngleDegrees = in.number();
  o.twoSided = in.boolean();
  o.twist = in.boolean();
  o.seed = in.integer<std::uint32_t>();
  o.lightOversampling = in.boolean();
  o.albedoPolicy = in.boolean() ? AlbedoPolicy::Clamp : AlbedoPolicy::Reject;
  o.backend = Backend(in.count(2));
  o.cudaDevices = in.integer<std::int8_t>();
  o.cudaBvhUpdate = CudaBvhUpdate(in.count(2));
  o.cudaBvhBuild = CudaBvhBuild(in.count(1));
  return o;
}

/// An open box (floor and three walls) lit from inside: 12 vertices, 8 triangles.
Scene box()
{
  Scene s;
  const Vec3f corner[4] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 1 }, { 0, 0, 1 } };
  const Vec3f up(0, 1, 0);
  for (int wall = 0; wall < 3; ++wall)
  {
    const Vec3f a = corner[wall], b = corner[wall + 1];
    const Index base = Index(s.positions.size());
    for (const Vec3f& p : { a, b, b + up, a + up })
    {
      s.positions.push_back(p);
      s.normals.push_back(normalize(Vec3f(0.5f, 0.f, 0.5f) - (a + b) * 0.5f));
      s.albedo.push_back(Vec3f(0.8f, 0.6f, 0.4f));
    }
    s.triangles.push_back({ { base, Index(base + 1), Index(base + 2) } });
    s.triangles.push_back({ { base, Index(base + 2), Index(base + 3) } });
  }
  s.lights.push_back(Light());
  s.lights[0].position = Vec3f(0.5f, 0.8f, 0.5f);
  return s;
}

/// The methods' own options, read after the scene so that inputs written before these were
/// fuzzed still decode to the same options and scene. An input that ends before them gets 16
/// VPLs, 512 photons, 16 clusters and 16 reference paths, not the product's 1024, 262144,
/// 4096 and 1024: the same code paths, at a fraction of the cost per execution.
void methodOptions(linkgi_fuzz::Input& in, SolverOptions& o)
{
  InstantRadiosityOptions& ir = o.instantRadiosity;
  ir.vplCount = 16;
  o.photonMapping.photons = 512;
  o.photonMapping.clusters = 16;
  o.reference.pathsPerVertex = 16;
  if (!in.boolean())
  {
    return;
  }
  ir.vplCount = in.count(7) ? std::uint32_t(in.count(256)) : in.integer<std::uint32_t>();
  ir.clampDistance = in.number();
  ir.interleave = in.count(7) ? std::uint32_t(in.count(16)) : in.integer<std::uint32_t>();
  ir.proxyVisibility = in.boolean();
  ir.proxyResolution = in.count(7) ? std::uint32_t(in.count(48)) : in.integer<std::uint32_t>();
  ir.russianRoulette = in.boolean();
  o.implicitVisibility.binsPerSide = in.count(7) ? std::uint32_t(in.count(16)) : in.integer<std::uint32_t>();
  PhotonMappingOptions& pm = o.photonMapping;
  pm.photons = in.count(7) ? std::uint32_t(in.count(4096)) : in.integer<std::uint32_t>();
  pm.clusters = in.count(7) ? std::uint32_t(in.count(64)) : in.integer<std::uint32_t>();
  const std::uint32_t g = std::uint32_t(in.count(16));
  pm.gatherRays = in.count(7) ? g * g : in.integer<std::uint32_t>();
  pm.estimatePhotons = in.count(7) ? std::uint32_t(in.count(128)) : in.integer<std::uint32_t>();
  pm.alpha = in.number();
  // 0 = no budget; a small one is an error naming it, a large one changes nothing.
  o.memoryBudget = in.boolean() ? in.integer<std::uint64_t>() : 0;
  if (in.boolean())
  {
    o.reference.pathsPerVertex = in.count(7) ? std::uint32_t(in.count(64)) : in.integer<std::uint32_t>();
  }
}

bool cheap(const SolverOptions& o)
{
  return o.raysPerVertex <= 1024 && o.bounces <= 64 && o.instantRadiosity.vplCount <= 4096 &&
    o.instantRadiosity.proxyResolution <= 64 && o.implicitVisibility.binsPerSide <= 16 &&
    o.photonMapping.photons <= 4096 && o.photonMapping.gatherRays <= 1024 &&
    o.reference.pathsPerVertex <= 256;
}

/// Solves; false when the update throws linkgi::Error (options or scene rejected).
bool solve(Solver& solver, const Scene& scene, const SolverOptions& o)
{
  try
  {
    validateOptions(o);
    if (!cheap(o))
    {
      return false;
    }
    solver.update(scene, o);
  }
  catch (const Error&)
  {
    return false;
  }
  const Solution& s = solver.solution();
  LINKGI_FUZZ_REQUIRE(s.elementCount() == scene.vertexCount() * (o.twoSided ? 2 : 1));
  LINKGI_FUZZ_REQUIRE(s.indirect.size() == s.elementCount() && s.radiance.size() == s.elementCount());
  for (std::size_t i = 0; i < s.elementCount(); ++i)
  {
    for (const Vec3f& v : { s.direct[i], s.indirect[i], s.radiance[i] })
    {
      LINKGI_FUZZ_REQUIRE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
      LINKGI_FUZZ_REQUIRE(v.x >= 0.f && v.y >= 0.f && v.z >= 0.f);
    }
  }
  return true;
}
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  linkgi_fuzz::Input in(data, size);
  SolverOptions first = options(in), second = options(in);
  const Scene scene = in.boolean() ? box() : linkgi_fuzz::scene(in);
  methodOptions(in, first);
  methodOptions(in, second);
  Solver solver;
  solve(solver, scene, first);
  Solver fresh;
  if (!solve(solver, scene, second) || !solve(fresh, scene, second))
  {
    return 0;
  }
  const Solution &a = solver.solution(), &b = fresh.solution();
  for (std::size_t i = 0; i < a.elementCount(); ++i)
  {
    LINKGI_FUZZ_REQUIRE(std::memcmp(&a.radiance[i], &b.radiance[i], sizeof(Vec3f)) == 0);
  }
  return 0;
}
