// Light paths from the lights, emissive surfaces and the sky, for the methods that shoot
// light (instant radiosity's VPLs, photon mapping's photons), on the CPU and the GPU alike
// (LINKGI_HOST_DEVICE): quasi-random numbers, the sources a path starts from, one path, and
// the host-side set-up both backends share (the source table, the second pass, the packed
// set of the paths' hits).
#pragma once

#include "cpu/Parallel.h"
#include "linkgi/SolverTypes.h"
#include "shared/DirectLight.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "shared/Sampling.h"

#include <cstdint>
#include <vector>

namespace linkgi::paths
{
/// One virtual point light: a diffuse emitter at a point, or a direction of the sky.
struct Vpl
{
  Vec3f position; ///< the surface point (shadow rays end `offset` off it along `normal`)
  Vec3f normal;   ///< unit normal of the side that emits; for a sky VPL the direction to the sky
  /// Surface VPL: reflected flux Phi / paths, so that E(x) = Phi/pi cos cos / d^2.
  /// Sky VPL: irradiance on a surface facing it, E(x) = flux * cos.
  Vec3f flux;
  std::uint32_t sky = 0;
  /// Left at a diffuse surface by a path that met only mirrors and glass since its light
  /// (light - specular+ - diffuse): photon mapping's caustic photons.
  std::uint32_t caustic = 0;
  float offset = 0.f; ///< the ray offset of the triangle it lies on (triangleOffset)
};

/// Kinds of light-path sources.
enum SourceKind : std::uint32_t
{
  kLightSource = 0,    ///< a point, spot or directional light (index into the lights)
  kEmitterSource = 1,  ///< an emissive triangle (index into the triangles)
  kEnvironmentSource = 2
};

/// One entry of the table a path picks its source from, in proportion to power.
struct Source
{
  std::uint32_t kind = kLightSource;
  Index index = 0;
  float probability = 0.f;
  float area = 0.f; ///< emitters: the triangle's area
};

/// What a light path reads; plain pointers so the GPU can hold the same.
struct PathScene
{
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const Vec3f* albedo = nullptr;
  const Vec3f* emission = nullptr; ///< null without emissive surfaces
  const Triangle* triangles = nullptr;
  const Vec3f* faceNormals = nullptr; ///< frontFaceNormals
  const Light* lights = nullptr;
  const Source* sources = nullptr;
  const float* cdf = nullptr; ///< sourceCount inclusive prefix sums of the probabilities
  Index sourceCount = 0;
  Vec3f centre;      ///< of the scene's bounding sphere
  float radius = 1.f; ///< of the scene's bounding sphere
  Vec3f envColor;
  int envWidth = 0, envHeight = 0;
  const Vec3f* envTexels = nullptr;
  std::uint32_t paths = 1;
  std::uint32_t bounces = 3;
  bool twoSided = false;
  bool russianRoulette = false;
  std::uint32_t seed = 0;
  const RayOrigin* origins = nullptr; ///< per vertex: paths leave a triangle by triangleOffset
  /// Per triangle (MaterialType), or null: every surface diffuse (instant radiosity lights
  /// mirrors and glass as diffuse; photon mapping passes them).
  const std::uint8_t* materials = nullptr;
  const float* ior = nullptr; ///< per triangle with materials, or null for 1.5
};

/// Mirror and glass bounces a light path may take besides its diffuse ones (total internal
/// reflection could otherwise keep it inside glass for ever).
constexpr std::uint32_t kMaxSpecularBounces = 16;

/// The shading normal at barycentric (1 - u - v, u, v) of triangle t, whose face normal is
/// fn: the vertex normals interpolated, or fn where they vanish or turn against it. What a
/// photon is stored with at a hit, and what reads photons there.
LINKGI_HOST_DEVICE inline Vec3f hitNormal(const PathScene& s, const Triangle& t, float u, float v, const Vec3f& fn)
{
  const Vec3f n = normalize(s.normals[t.v[0]] * (1.f - u - v) + s.normals[t.v[1]] * u + s.normals[t.v[2]] * v);
  return dot(n, n) > 0.f && dot(n, fn) > 0.f ? n : fn;
}

/// Reflection of unit d about unit n.
LINKGI_HOST_DEVICE inline Vec3f reflect(const Vec3f& d, const Vec3f& n)
{
  return d - n * (2.f * dot(d, n));
}

/// Where a ray of unit direction d goes at a smooth dielectric with unit normal n (pointing
/// to the side d comes from) and relative index eta = n_from / n_to: reflected with the exact
/// Fresnel reflectance (unpolarized), refracted otherwise, picked by u in [0, 1).
LINKGI_HOST_DEVICE inline Vec3f dielectricDirection(const Vec3f& d, const Vec3f& n, float eta, float u)
{
  const float cosi = fminf(1.f, -dot(d, n));
  const float sin2t = eta * eta * fmaxf(0.f, 1.f - cosi * cosi);
  if (sin2t >= 1.f)
  {
    return reflect(d, n); // total internal reflection
  }
  const float cost = std::sqrt(1.f - sin2t);
  const float rs = (eta * cosi - cost) / (eta * cosi + cost), rp = (cosi - eta * cost) / (cosi + eta * cost);
  const float fresnel = 0.5f * (rs * rs + rp * rp);
  if (u < fresnel)
  {
    return reflect(d, n);
  }
  return d * eta + n * (eta * cosi - cost);
}

/// Radical inverse of `index` in `base` (one Halton dimension).
LINKGI_HOST_DEVICE inline float radicalInverse(std::uint32_t base, std::uint32_t index)
{
  const float inv = 1.f / float(base);
  float f = inv, r = 0.f;
  while (index > 0)
  {
    r += f * float(index % base);
    index /= base;
    f *= inv;
  }
  return r;
}

/// Dimension `dim` of the Halton point `index`, shifted modulo 1 by a per-dimension offset of
/// the seed (Cranley-Patterson rotation), so each seed gives another, equally uniform, set.
/// Past the 32nd dimension (long paths) hashed numbers replace the sequence.
LINKGI_HOST_DEVICE inline float halton(std::uint32_t index, std::uint32_t dim, std::uint32_t seed)
{
  constexpr std::uint32_t kPrimes[32] = { 2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53,
    59, 61, 67, 71, 73, 79, 83, 89, 97, 101, 103, 107, 109, 113, 127, 131 };
  if (dim >= 32)
  {
    return hashToUnit(seed ^ hash32(dim), index);
  }
  const float u = radicalInverse(kPrimes[dim], index) + hashToUnit(seed, dim);
  const float wrapped = u >= 1.f ? u - 1.f : u;
  return wrapped < 1.f ? wrapped : 0.99999994f;
}

/// Radiance of the environment seen along unit direction d (Environment::radiance).
LINKGI_HOST_DEVICE inline Vec3f skyRadiance(const PathScene& s, const Vec3f& d)
{
  return s.envWidth > 0 ? s.envColor * s.envTexels[environmentTexel(s.envWidth, s.envHeight, d)] : s.envColor;
}

/// A uniform direction on the unit sphere.
LINKGI_HOST_DEVICE inline Vec3f uniformSphere(float u, float v)
{
  const float z = 1.f - 2.f * u, r = std::sqrt(fmaxf(0.f, 1.f - z * z)), phi = 2.f * kPi * v;
  return { r * std::cos(phi), r * std::sin(phi), z };
}

/// A point of the disk of radius `radius` about `centre` perpendicular to unit `axis`.
LINKGI_HOST_DEVICE inline Vec3f diskPoint(const Vec3f& centre, const Vec3f& axis, float radius, float u, float v)
{
  float x, y;
  concentricDisk(u, v, x, y);
  const Frame f = Frame::fromNormal(axis);
  return centre + f.t * (x * radius) + f.b * (y * radius);
}

/// The cone of directions in which a point or spot light's paths leave: `axis` and one minus
/// the cosine of its half angle. A point light sends light everywhere, a spot light within
/// its cone; from outside the scene's bounding sphere (`centre`, `radius`) only directions
/// within the sphere's cone can reach a surface, and the narrower of the two cones is
/// sampled: a lamp beside a model alone would otherwise spend most of its paths on nothing
/// (a lamp 1.4 diagonals from a model lands one path in 30). One minus the cosine, not the
/// cosine, so that the cone of a lamp thousands of radii away keeps its width in single
/// precision (its cosine rounds to 1 beyond about 4,000 radii).
struct EmissionCone
{
  Vec3f axis{ 0.f, 0.f, 1.f };
  float oneMinusCos = 2.f; ///< 2: the whole sphere of directions
  LINKGI_HOST_DEVICE float solidAngle() const { return 2.f * kPi * oneMinusCos; }
  /// The direction of the cone at (u, v) in [0, 1)^2, uniform in solid angle.
  LINKGI_HOST_DEVICE Vec3f direction(float u, float v) const
  {
    const float x = u * oneMinusCos; // 1 - cos of the angle to the axis
    const float sinAxis = std::sqrt(fmaxf(0.f, x * (2.f - x))), phi = 2.f * kPi * v;
    return Frame::fromNormal(axis).toWorld({ sinAxis * std::cos(phi), sinAxis * std::sin(phi), 1.f - x });
  }
};

LINKGI_HOST_DEVICE inline EmissionCone emissionCone(const Light& l, const Vec3f& centre, float radius)
{
  EmissionCone cone;
  if (l.type == LightType::Spot)
  {
    const float half = std::sin(0.5f * l.coneAngleDegrees * (kPi / 180.f));
    cone = { normalize(l.direction), 2.f * half * half };
  }
  const Vec3f toCentre = centre - l.position;
  const float distance = length(toCentre);
  // A little wider than the sphere, for the roundings of the distance and the directions.
  const float reach = radius * 1.001f;
  if (distance > reach)
  {
    const float sinScene = reach / distance;
    const float cosScene = std::sqrt(fmaxf(0.f, 1.f - sinScene * sinScene));
    const float scene = sinScene * sinScene / (1.f + cosScene);
    if (scene < cone.oneMinusCos)
    {
      cone = { toCentre * (1.f / distance), scene };
    }
  }
  return cone;
}

/// The source the path picks with u in [0, 1): the first cdf entry above u.
LINKGI_HOST_DEVICE inline Index pickSource(const float* cdf, Index count, float u)
{
  Index lo = 0, hi = count - 1;
  while (lo < hi)
  {
    const Index mid = (lo + hi) / 2;
    if (cdf[mid] > u)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

/// Light path `path` of s.paths: its VPLs into out[0, bounces + 1); returns how many. A path
/// leaves a VPL where it starts on an emitter (its light reaches vertices unreflected) or
/// in the sky, and one at every diffuse hit whose light reaches vertices after at most
/// `bounces` reflections in all: bounces hits from lights and the sky, bounces - 1 from an
/// emitter, as the link method's Jacobi bounces and the reference count them.
/// `trace(ray)` returns the closest Hit.
template <typename Trace>
LINKGI_HOST_DEVICE int traceLightPath(const PathScene& s, std::uint32_t path, Vpl* out, const Trace& trace)
{
  if (s.sourceCount == 0)
  {
    return 0;
  }
  const std::uint32_t index = path + 1; // Halton point 0 is the origin in every dimension
  const auto u = [&](std::uint32_t dim) { return halton(index, dim, s.seed); };
  const Source src = s.sources[pickSource(s.cdf, s.sourceCount, u(0))];
  const float scale = 1.f / (src.probability * float(s.paths));
  int count = 0;
  Ray ray;
  Vec3f power; // flux this path carries, per path already
  std::uint32_t hits = s.bounces;
  if (src.kind == kLightSource)
  {
    const Light& l = s.lights[src.index];
    if (l.type == LightType::Directional)
    {
      const Vec3f axis = normalize(l.direction);
      ray.origin = diskPoint(s.centre - axis * (1.5f * s.radius), axis, s.radius, u(1), u(2));
      ray.direction = axis;
      power = l.intensity * (kPi * s.radius * s.radius * scale);
    }
    else
    {
      // Uniform in the cone that reaches the scene (emissionCone); a spot light's own cone
      // and falloff weigh each direction.
      const EmissionCone cone = emissionCone(l, s.centre, s.radius);
      ray.origin = l.position;
      ray.direction = cone.direction(u(3), u(4));
      const float spot = spotFactor(l, ray.direction);
      if (!(spot > 0.f))
      {
        return 0; // outside a spot light's cone, within the scene's
      }
      power = l.intensity * (spot * cone.solidAngle() * scale);
    }
  }
  else if (src.kind == kEmitterSource)
  {
    const Triangle t = s.triangles[src.index];
    const float su = std::sqrt(u(1)), b1 = u(2) * su, b0 = 1.f - su, b2 = 1.f - b0 - b1;
    const Vec3f p = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * b1 + s.positions[t.v[2]] * b2;
    Vec3f n = normalize(s.normals[t.v[0]] * b0 + s.normals[t.v[1]] * b1 + s.normals[t.v[2]] * b2);
    if (!(dot(n, n) > 0.f))
    {
      n = s.faceNormals[src.index];
    }
    const Vec3f le = s.emission[t.v[0]] * b0 + s.emission[t.v[1]] * b1 + s.emission[t.v[2]] * b2;
    power = le * (kPi * src.area * scale);
    const float offset = triangleOffset(s.origins, t);
    out[count++] = { p, n, power, 0u, 0u, offset };
    if (s.bounces == 0)
    {
      return count;
    }
    hits = s.bounces - 1;
    ray.origin = p + n * offset;
    ray.direction = Frame::fromNormal(n).toWorld(cosineHemisphere(u(3), u(4)));
  }
  else
  {
    const Vec3f toSky = uniformSphere(u(3), u(4));
    const Vec3f l = skyRadiance(s, toSky);
    out[count++] = { Vec3f(0.f), toSky, l * (4.f * kPi * scale), 1u };
    ray.origin = diskPoint(s.centre + toSky * (1.5f * s.radius), toSky, s.radius, u(1), u(2));
    ray.direction = -toSky;
    power = l * (4.f * kPi * kPi * s.radius * s.radius * scale);
  }
  ray.tnear = 0.f;
  ray.tfar = 3.0e38f;
  // Only specular bounces since the light (or an emitter, which is diffuse): a diffuse hit
  // then leaves a caustic photon.
  bool onlySpecular = src.kind == kLightSource;
  // From a point or spot light: the path's length to its first diffuse hit, where it takes
  // the light's falloff against 1/r^2 (falloffAgainstInverseSquare).
  const bool fromPosition = src.kind == kLightSource && s.lights[src.index].type != LightType::Directional;
  bool landed = !fromPosition;
  float travelled = 0.f;
  bool metSpecular = false;
  std::uint32_t specular = 0;
  for (std::uint32_t bounce = 0; bounce < hits;)
  {
    const Hit h = trace(ray);
    if (h.triangle == kInvalidIndex)
    {
      break;
    }
    travelled += landed ? 0.f : h.t * length(ray.direction);
    const Vec3f fn = s.faceNormals[h.triangle];
    const bool back = dot(ray.direction, fn) > 0.f;
    const Triangle t = s.triangles[h.triangle];
    const float b0 = 1.f - h.u - h.v;
    const Vec3f p = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * h.u + s.positions[t.v[2]] * h.v;
    const Vec3f n = hitNormal(s, t, h.u, h.v, fn);
    const std::uint8_t material = s.materials ? s.materials[h.triangle] : 0u;
    if (material != 0u)
    {
      // A mirror or glass: the path turns without losing power or leaving a VPL, and does
      // not count as one of the bounces.
      if (++specular > kMaxSpecularBounces)
      {
        break;
      }
      const Vec3f d = normalize(ray.direction), facing = back ? -n : n;
      Vec3f next;
      if (material == 1u)
      {
        next = reflect(d, facing);
      }
      else
      {
        const float ior = s.ior ? s.ior[h.triangle] : 1.5f;
        next = dielectricDirection(d, facing, back ? ior : 1.f / ior, u(40 + specular));
      }
      const Vec3f geometric = dot(next, fn) > 0.f ? fn : -fn; // the side the path leaves by
      ray.origin = p + geometric * triangleOffset(s.origins, t);
      ray.direction = next;
      ray.tnear = 0.f;
      ray.tfar = 3.0e38f;
      metSpecular = true;
      continue;
    }
    if (back && !s.twoSided)
    {
      break; // the back of a one-sided surface is black
    }
    const Vec3f side = back ? -n : n, geometric = back ? -fn : fn;
    const Vec3f rho = s.albedo[t.v[0]] * b0 + s.albedo[t.v[1]] * h.u + s.albedo[t.v[2]] * h.v;
    if (!landed)
    {
      power = power * falloffAgainstInverseSquare(s.lights[src.index], travelled * travelled);
      landed = true;
    }
    power = power * rho;
    const float offset = triangleOffset(s.origins, t);
    const Vec3f origin = p + geometric * offset;
    out[count++] = { p, side, power, 0u, onlySpecular && metSpecular ? 1u : 0u, offset };
    onlySpecular = false;
    if (++bounce == hits)
    {
      break;
    }
    const std::uint32_t dim = 5 + 3 * (bounce - 1);
    if (s.russianRoulette)
    {
      // rho is in the power already: continuing with probability q and dividing by it keeps
      // the estimate unbiased.
      const float q = fminf(1.f, fmaxf(rho.x, fmaxf(rho.y, rho.z)));
      if (!(u(dim + 2) < q))
      {
        break;
      }
      power = power / q;
    }
    ray.origin = origin;
    ray.direction = Frame::fromNormal(side).toWorld(cosineHemisphere(u(dim), u(dim + 1)));
    ray.tnear = 0.f;
    ray.tfar = 3.0e38f;
  }
  return count;
}

/// The sources a light path starts from, picked in proportion to their power, and the
/// PathScene over host arrays (a GPU backend swaps in its device pointers).
struct PathSetup
{
  std::vector<Source> sources;
  std::vector<float> cdf;
  PathScene view;
  /// Surface VPLs closer than 0.8 * dmin to a vertex give it nothing (distanceBound).
  float dmin = 0.f;
  /// The VPLs asked for (InstantRadiosityOptions::vplCount).
  std::uint32_t targetVpls = 1;
};

/// ceil(vplCount / bounces) paths (vplCount with no bounces): about vplCount VPLs where
/// every path stays in the scene.
std::uint32_t pathCount(const SolverOptions& options);

/// Paths for a second pass when the first pass of `paths` left `found` VPLs, fewer than half
/// the `target` (in an open scene most paths leave it): enough for about `target` at the
/// rate seen, at most 64 times the first pass and 2^22 VPL slots; 0 to keep the first pass.
/// Both backends ask it, so they trace the same paths.
std::uint32_t secondPassPaths(std::uint32_t paths, std::size_t found, std::uint32_t target,
  std::uint32_t slotsPerPath);

/// Sources of `scene` (validated) and the view over its arrays and `faceNormals`
/// (frontFaceNormals). Lights start paths only when bounces > 0 (their direct light is the
/// light-link stage's). A scene with no source gets an empty table and no VPLs. `extent`:
/// sceneExtent(scene) where the caller kept it (computed here otherwise).
PathSetup buildPathSetup(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const SolverOptions& options, const SceneExtent* extent = nullptr);

/// A VPL set: VPLs of subset r are [subsetOffsets[r], subsetOffsets[r + 1]), each subset a
/// contiguous run of light paths (a run of the Halton sequence is itself well spread),
/// scaled by subsetScale[r] = paths / paths in subset r when a vertex gathers only it.
struct VplSet
{
  std::vector<Vpl> vpls;
  std::vector<std::uint32_t> subsetOffsets;
  std::vector<float> subsetScale;
  /// Bytes of the second pass's path slots (0 without one; the first pass's are freed
  /// before they are allocated): memory that the update's estimate, made before the first
  /// pass, did not count.
  std::uint64_t secondPassBytes = 0;
  std::size_t count() const { return vpls.size(); }
};

/// First path of subset r of `subsets` over `paths` paths.
LINKGI_HOST_DEVICE inline std::uint32_t subsetFirstPath(std::uint32_t r, std::uint32_t subsets, std::uint32_t paths)
{
  return std::uint32_t(std::uint64_t(r) * paths / subsets);
}

/// Packs per-path VPL slots (bounces + 1 per path, counts[i] used) into a VplSet.
VplSet packVpls(const std::vector<Vpl>& slots, const std::vector<int>& counts,
  std::uint32_t slotsPerPath, std::uint32_t subsets);

/// Every light path of `setup` traced against `tracer` (the mesh), split into `subsets`.
/// A scene whose paths mostly leave it gets a second pass of more paths (secondPassPaths);
/// when that pass's slots would take more than `secondPassBytes`, OutOfMemoryBudget says so
/// before they are allocated (the update's estimate counts the first pass only), and
/// otherwise VplSet::secondPassBytes says what they took.
VplSet traceVplsCpu(const PathSetup& setup, const RayTracer& tracer, std::uint32_t subsets,
  const ProgressCallback& progress = {}, std::uint64_t secondPassBytes = UINT64_MAX);
}
