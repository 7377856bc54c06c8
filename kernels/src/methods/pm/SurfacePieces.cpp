// The mesh cut into pieces small enough for photon mapping's estimates to measure the area
// their ball of photons cuts from the surface (surfacePieces, SurfaceTree: PhotonMapping.h;
// the measure itself is photonArea, PmMath.h).
#include "methods/pm/PhotonMapping.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace linkgi::pm
{
namespace
{
constexpr float kInfinity = std::numeric_limits<float>::max();

/// Cuts of one triangle at most, so at most 2^kBisections pieces of it: a large face of a
/// CAD part needs some 16; beyond, pieces stay longer (their areas in a ball stay exact).
constexpr int kBisections = 20;

/// Calls emit(a, b, c, barycentric centroid) for the pieces of triangle (a, b, c) cut by
/// halving its longest edge until no edge is longer than sqrt(edge2) (or `depth` is spent);
/// returns how many (emit may do nothing, to count them). Longest-edge bisection keeps the
/// pieces' angles bounded.
template <typename Emit>
std::uint64_t bisect(const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec3f& ua, const Vec3f& ub,
  const Vec3f& uc, float edge2, int depth, const Emit& emit)
{
  const float ab = dot(b - a, b - a), bc = dot(c - b, c - b), ca = dot(a - c, a - c);
  const float longest = std::max({ ab, bc, ca });
  if (!(longest > edge2) || depth == 0)
  {
    emit(a, b, c, (ua + ub + uc) * (1.f / 3.f));
    return 1;
  }
  --depth;
  if (longest == ab)
  {
    const Vec3f m = (a + b) * 0.5f, um = (ua + ub) * 0.5f;
    return bisect(a, m, c, ua, um, uc, edge2, depth, emit) + bisect(m, b, c, um, ub, uc, edge2, depth, emit);
  }
  if (longest == bc)
  {
    const Vec3f m = (b + c) * 0.5f, um = (ub + uc) * 0.5f;
    return bisect(a, b, m, ua, ub, um, edge2, depth, emit) + bisect(a, m, c, ua, um, uc, edge2, depth, emit);
  }
  const Vec3f m = (c + a) * 0.5f, um = (uc + ua) * 0.5f;
  return bisect(a, b, m, ua, ub, um, edge2, depth, emit) + bisect(m, b, c, um, ub, uc, edge2, depth, emit);
}
}

SurfacePieces surfacePieces(const Scene& scene)
{
  const std::vector<Vec3f>& x = scene.positions;
  double total = 0.0;
  for (const Triangle& t : scene.triangles)
  {
    total += 0.5 * double(length(cross(x[t.v[1]] - x[t.v[0]], x[t.v[2]] - x[t.v[0]])));
  }
  const Vec3f u0(1.f, 0.f, 0.f), u1(0.f, 1.f, 0.f), u2(0.f, 0.f, 1.f);
  const auto count = [](const Vec3f&, const Vec3f&, const Vec3f&, const Vec3f&) {};
  // No cut where that edge rounds to zero (a surface some 1e-20 of a metre across).
  float edge2 = float(4.0 * total / kSurfacePieces);
  edge2 = edge2 > std::numeric_limits<float>::min() ? edge2 : kInfinity;
  std::uint64_t added = 0;
  for (int attempt = 0; attempt < 16; ++attempt, edge2 *= 4.f)
  {
    added = 0;
    for (std::size_t t = 0; t < scene.triangles.size() && added <= kSurfacePieces; ++t)
    {
      const Triangle& tri = scene.triangles[t];
      added += bisect(x[tri.v[0]], x[tri.v[1]], x[tri.v[2]], u0, u1, u2, edge2, kBisections, count) - 1;
    }
    if (added <= kSurfacePieces)
    {
      break;
    }
  }
  if (added > kSurfacePieces) // slivers of almost no area: the triangles whole
  {
    edge2 = kInfinity;
    added = 0;
  }
  SurfacePieces out;
  const std::size_t pieces = scene.triangles.size() + std::size_t(std::min<std::uint64_t>(added, kSurfacePieces));
  out.centroids.reserve(pieces);
  out.normals.reserve(pieces);
  out.areas.reserve(pieces);
  out.radii.reserve(pieces);
  out.corners.reserve(3 * pieces);
  float reach2 = 0.f;
  for (const Triangle& t : scene.triangles)
  {
    bisect(x[t.v[0]], x[t.v[1]], x[t.v[2]], u0, u1, u2, edge2, kBisections, [&](const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec3f& w) {
      const Vec3f centroid = (a + b + c) * (1.f / 3.f);
      const Vec3f n = scene.normals[t.v[0]] * w.x + scene.normals[t.v[1]] * w.y + scene.normals[t.v[2]] * w.z;
      out.centroids.push_back(centroid);
      out.normals.push_back(unitOr(n, scene.normals[t.v[0]]));
      out.areas.push_back(0.5f * length(cross(b - a, c - a)));
      float radius2 = 0.f;
      for (const Vec3f* p : { &a, &b, &c })
      {
        out.corners.push_back(*p);
        radius2 = std::max(radius2, dot(*p - centroid, *p - centroid));
      }
      out.radii.push_back(std::sqrt(radius2));
      reach2 = std::max(reach2, radius2);
    });
  }
  out.reach = std::sqrt(reach2);
  return out;
}

SurfaceTree::SurfaceTree(const Scene& scene)
  : pieces(surfacePieces(scene))
  , tree(pieces.centroids)
{
}

SurfaceView SurfaceTree::view(bool twoSided) const
{
  return { tree.view(), pieces.corners.data(), pieces.normals.data(), pieces.areas.data(), pieces.radii.data(),
    pieces.reach, twoSided };
}

}
