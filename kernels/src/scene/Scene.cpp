#include "linkgi/Scene.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <sstream>

namespace linkgi
{
bool Environment::isBlack() const
{
  return maxComponent(color) <= 0.f;
}

Index Environment::texelIndex(const Vec3f& d) const
{
  if (!hasTexture())
  {
    return 0;
  }
  return environmentTexel(width, height, d);
}

Vec3f Environment::radiance(const Vec3f& d) const
{
  return hasTexture() ? color * texels[texelIndex(d)] : color;
}

bool sameScene(const Scene& a, const Scene& b)
{
  return sameBits(a.positions, b.positions) && sameBits(a.normals, b.normals) &&
    sameBits(a.albedo, b.albedo) && sameBits(a.emission, b.emission) &&
    sameBits(a.triangles, b.triangles) && sameBits(a.triangleMaterials, b.triangleMaterials) &&
    sameBits(a.triangleIor, b.triangleIor) && sameBits(a.lights, b.lights) &&
    a.environment.color == b.environment.color && a.environment.width == b.environment.width &&
    a.environment.height == b.environment.height && sameBits(a.environment.texels, b.environment.texels) &&
    a.lengthExponent == b.lengthExponent;
}

namespace
{
/// Items per range of the scans over a mesh's arrays on all cores: one core scans a
/// 121k-vertex mesh's arrays in milliseconds, which a deformation on the GPU waited for.
constexpr std::size_t kScanGrain = 16384;
}

void positionBounds(const std::vector<Vec3f>& positions, Vec3f& lo, Vec3f& hi)
{
  const Vec3f start = positions.empty() ? Vec3f(0.f) : positions[0];
  lo = hi = start;
  std::mutex mutex;
  parallelRanges(positions.size(), kScanGrain, [&](std::size_t begin, std::size_t end) {
    // Every range starts from the first position, as one pass over all would.
    Vec3f l = start, h = start;
    for (std::size_t i = begin; i < end; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        l[k] = std::min(l[k], positions[i][k]);
        h[k] = std::max(h[k], positions[i][k]);
      }
    }
    std::lock_guard<std::mutex> lock(mutex);
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], l[k]);
      hi[k] = std::max(hi[k], h[k]);
    }
  });
}

float boxDiagonal(const Vec3f& lo, const Vec3f& hi)
{
  double squared = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double extent = double(hi[k]) - double(lo[k]);
    squared += extent * extent;
  }
  return static_cast<float>(std::min(std::sqrt(squared), double(std::numeric_limits<float>::max())));
}

float boundingDiagonal(const std::vector<Vec3f>& positions)
{
  Vec3f lo, hi;
  positionBounds(positions, lo, hi);
  return boxDiagonal(lo, hi);
}

namespace
{
[[noreturn]] void fail(const std::string& what)
{
  throw Error(what);
}

template <typename Check>
void checkArray(const std::vector<Vec3f>& values, const char* name, Check isBad, const char* problem)
{
  const std::size_t i =
    firstIndexWhere(values.size(), kScanGrain, [&](std::size_t j) { return isBad(values[j]); });
  if (i < values.size())
  {
    std::ostringstream msg;
    msg << "Vertex " << i << " has " << problem << " " << name << " (" << values[i].x << ", "
        << values[i].y << ", " << values[i].z << ").";
    fail(msg.str());
  }
}

// Function objects, not functions: checkArray inlines them (through a function pointer
// the checks cost more than the rest of a light update on a large mesh).
constexpr auto notFinite = [](const Vec3f& v) { return !isFinite(v); };
constexpr auto negativeOrNotFinite = [](const Vec3f& v) {
  // One comparison per channel: false for negative values, NaN and +Inf alike.
  constexpr float kMax = 3.402823466e38f;
  return !(v.x >= 0.f && v.x <= kMax && v.y >= 0.f && v.y <= kMax && v.z >= 0.f && v.z <= kMax);
};
/// Emitted radiance above this is an error: gathered over the bounces (up to 1000) it would
/// leave single precision (an emission of 3.4e38 gave infinite radiance).
constexpr float kBrightest = 1e30f;
constexpr auto negativeOrTooBright = [](const Vec3f& v) {
  return !(v.x >= 0.f && v.x <= kBrightest && v.y >= 0.f && v.y <= kBrightest && v.z >= 0.f &&
    v.z <= kBrightest);
};

/// `n` at unit length, zero for a zero vector. Scaled first by the power of two of its
/// largest component (exact, and no reciprocal of a denormal), so that the squares neither
/// overflow (1e20, 0, 0) nor underflow (1e-30, 0, 0) to a length of infinity or zero.
Vec3f unitLength(const Vec3f& n)
{
  const float largest = std::max({ std::abs(n.x), std::abs(n.y), std::abs(n.z) });
  if (!(largest > 0.f))
  {
    return Vec3f(0.f);
  }
  const int e = std::ilogb(largest);
  return normalize(Vec3f(std::ldexp(n.x, -e), std::ldexp(n.y, -e), std::ldexp(n.z, -e)));
}

void checkLights(const std::vector<Light>& lights)
{
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const Light& l = lights[i];
    const bool finite = isFinite(l.position) && isFinite(l.direction) && isFinite(l.intensity) &&
      std::isfinite(l.coneAngleDegrees) && std::isfinite(l.spotExponent) && isFinite(l.attenuation);
    if (!finite)
    {
      fail("Light " + std::to_string(i) + " has a non-finite position, direction or intensity.");
    }
    if (l.intensity.x < 0.f || l.intensity.y < 0.f || l.intensity.z < 0.f)
    {
      fail("Light " + std::to_string(i) + " has a negative intensity.");
    }
    const Vec3f& a = l.attenuation;
    if (l.type != LightType::Directional &&
      (a.x < 0.f || a.y < 0.f || a.z < 0.f || (a.x == 0.f && a.y == 0.f && a.z == 0.f)))
    {
      fail("Light " + std::to_string(i) + " has a negative attenuation, or one of zero "
        "everywhere (no constant, linear or quadratic term); give it (0, 0, 1) for a "
        "physical 1/r^2 falloff or (1, 0, 0) for none.");
    }
    if (l.type != LightType::Point && unitLength(l.direction) == Vec3f(0.f))
    {
      fail("Light " + std::to_string(i) + " is a spot or directional light without a direction.");
    }
  }
}

/// Ray origins beyond 2^60 (1.15e18) are invalid for Embree (its limit is about 1.8e18) and
/// lose all precision in ours: positions and point or spot lights must lie within.
bool withinRayRange(const Vec3f& p)
{
  constexpr float kRayRange = 1.152921504606846976e18f; // 2^60
  return std::abs(p.x) <= kRayRange && std::abs(p.y) <= kRayRange && std::abs(p.z) <= kRayRange;
}

/// Gives the lights unit directions (a direction of (1e20, 0, 0) would overflow at use),
/// and multiplies point and spot positions by 2^-exponent and their intensities by
/// 4^-exponent (see Scene::lengthExponent; a directional light has no position). Throws
/// where a position or an intensity leaves float range.
void scaleLights(std::vector<Light>& lights, int exponent)
{
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    Light& l = lights[i];
    l.direction = unitLength(l.direction);
    if (exponent == 0 || l.type == LightType::Directional)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      l.position[k] = std::ldexp(l.position[k], -exponent);
      l.intensity[k] = std::ldexp(l.intensity[k], -2 * exponent);
    }
    // intensity / (c + l r + q r^2) unchanged with r and the intensity rescaled as above.
    l.attenuation.x = std::ldexp(l.attenuation.x, -2 * exponent);
    l.attenuation.y = std::ldexp(l.attenuation.y, -exponent);
    if (!isFinite(l.position))
    {
      fail("Light " + std::to_string(i) + " is so far from a scene this small that its "
        "position, in the scene's size, exceeds single precision; move it closer or scale "
        "the data up.");
    }
  }
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const Light& l = lights[i];
    if (l.type != LightType::Directional && !withinRayRange(l.position))
    {
      fail("Light " + std::to_string(i) + " is more than 2^60 scene units from the origin "
        "(after the scene's rescaling), beyond what ray tracing in single precision accepts "
        "as a ray origin; move it closer, or use a directional light for a distant source.");
    }
    if (!isFinite(l.intensity))
    {
      fail("Light " + std::to_string(i) + " is so bright for a scene this small that the "
        "irradiance it gives (intensity / r^2) exceeds single precision; lower its intensity "
        "or scale the data up.");
    }
  }
}

/// Rescales a scene far from unit size by a power of two (Scene::lengthExponent): exact, so
/// results do not change, and ray tests and 1/r^2 stay within single precision. A scene of
/// ordinary size far from the origin (a metre-wide part at 1e20) keeps huge coordinates,
/// which no ray can start from: an error.
void normalizeLength(Scene& scene)
{
  constexpr int kFarExponent = 16;
  Vec3f lo, hi;
  positionBounds(scene.positions, lo, hi);
  const float diagonal = boxDiagonal(lo, hi);
  const int exponent = diagonal > 0.f ? std::ilogb(diagonal) : 0;
  scene.lengthExponent = std::abs(exponent) > kFarExponent ? exponent : 0;
  const auto scaled = [&](const Vec3f& p)
  {
    return Vec3f(std::ldexp(p.x, -scene.lengthExponent), std::ldexp(p.y, -scene.lengthExponent),
      std::ldexp(p.z, -scene.lengthExponent));
  };
  if (!withinRayRange(scaled(lo)) || !withinRayRange(scaled(hi)))
  {
    fail("The scene lies more than 2^60 scene units (after rescaling) from the origin, beyond "
         "what ray tracing in single precision accepts; translate the data towards the origin.");
  }
  if (scene.lengthExponent == 0)
  {
    return;
  }
  for (Vec3f& p : scene.positions)
  {
    p = scaled(p);
  }
}

bool isDegenerate(const Scene& scene, const Triangle& t)
{
  if (t.v[0] == t.v[1] || t.v[1] == t.v[2] || t.v[0] == t.v[2])
  {
    return true;
  }
  const Vec3f& a = scene.positions[t.v[0]];
  const Vec3f n = cross(scene.positions[t.v[1]] - a, scene.positions[t.v[2]] - a);
  return !(dot(n, n) > 0.f);
}

/// The first triangle with repeated indices or zero area, or the triangle count.
std::size_t firstDegenerateTriangle(const Scene& scene)
{
  return firstIndexWhere(scene.triangles.size(), kScanGrain,
    [&scene](std::size_t i) { return isDegenerate(scene, scene.triangles[i]); });
}

/// Removes the degenerate triangles from `first` (the first of them) on, and their
/// materials and indices of refraction; returns how many were removed.
std::size_t removeDegenerateTriangles(Scene& scene, std::size_t first)
{
  const std::size_t before = scene.triangles.size();
  const auto degenerate = [&scene](const Triangle& t) { return isDegenerate(scene, t); };
  std::size_t kept = first;
  for (std::size_t i = first; i < before; ++i)
  {
    if (degenerate(scene.triangles[i]))
    {
      continue;
    }
    scene.triangles[kept] = scene.triangles[i];
    if (!scene.triangleMaterials.empty())
    {
      scene.triangleMaterials[kept] = scene.triangleMaterials[i];
    }
    if (!scene.triangleIor.empty())
    {
      scene.triangleIor[kept] = scene.triangleIor[i];
    }
    ++kept;
  }
  scene.triangles.resize(kept);
  if (!scene.triangleMaterials.empty())
  {
    scene.triangleMaterials.resize(kept);
  }
  if (!scene.triangleIor.empty())
  {
    scene.triangleIor.resize(kept);
  }
  return before - kept;
}

/// Materials and indices of refraction: one per triangle, known types, IOR > 0 and finite.
void checkMaterials(const Scene& scene)
{
  const std::size_t t = scene.triangles.size();
  if (!scene.triangleMaterials.empty() && scene.triangleMaterials.size() != t)
  {
    fail("The scene has " + std::to_string(scene.triangleMaterials.size()) + " triangle materials for " +
      std::to_string(t) + " triangles; give one per triangle (or none: all diffuse).");
  }
  if (!scene.triangleIor.empty() && scene.triangleIor.size() != t)
  {
    fail("The scene has " + std::to_string(scene.triangleIor.size()) + " indices of refraction for " +
      std::to_string(t) + " triangles; give one per triangle (or none: 1.5).");
  }
  const std::vector<MaterialType>& materials = scene.triangleMaterials;
  if (const std::size_t i = firstIndexWhere(materials.size(), kScanGrain,
        [&](std::size_t j) { return std::uint8_t(materials[j]) > std::uint8_t(MaterialType::Glass); });
      i < materials.size())
  {
    fail("Triangle " + std::to_string(i) + " has material " + std::to_string(int(materials[i])) +
      "; the materials are 0 (diffuse), 1 (mirror) and 2 (glass).");
  }
  const std::vector<float>& ior = scene.triangleIor;
  if (const std::size_t i = firstIndexWhere(ior.size(), kScanGrain,
        [&](std::size_t j) { return !(ior[j] > 0.f) || !std::isfinite(ior[j]); });
      i < ior.size())
  {
    fail("Triangle " + std::to_string(i) + " has index of refraction " + std::to_string(ior[i]) +
      "; an index of refraction is a finite number above 0 (glass: about 1.5).");
  }
}

/// Replaces zero-length normals by the area-weighted normal of the adjacent triangles (+Z
/// for a vertex of no triangle, or of triangles that cancel: any direction will do).
std::size_t repairNormals(Scene& scene)
{
  const auto unit = [&scene](std::size_t i) {
    const float len = length(scene.normals[i]);
    return len > 0.f && std::abs(len - 1.f) < 1e-3f;
  };
  std::vector<Vec3f> faceSum;
  std::size_t repaired = 0;
  const std::size_t first =
    firstIndexWhere(scene.normals.size(), kScanGrain, [&unit](std::size_t i) { return !unit(i); });
  for (std::size_t i = first; i < scene.normals.size(); ++i)
  {
    if (unit(i))
    {
      continue;
    }
    const Vec3f unit = unitLength(scene.normals[i]);
    if (unit != Vec3f(0.f))
    {
      scene.normals[i] = unit; // merely unnormalized: not worth a warning
      continue;
    }
    if (faceSum.empty())
    {
      faceSum.assign(scene.positions.size(), Vec3f(0.f));
      for (const Triangle& t : scene.triangles)
      {
        const Vec3f& a = scene.positions[t.v[0]];
        const Vec3f n = cross(scene.positions[t.v[1]] - a, scene.positions[t.v[2]] - a);
        for (Index v : t.v)
        {
          faceSum[v] += n;
        }
      }
    }
    const Vec3f face = unitLength(faceSum[i]);
    scene.normals[i] = face != Vec3f(0.f) ? face : Vec3f(0.f, 0.f, 1.f);
    ++repaired;
  }
  return repaired;
}
}

namespace
{
void checkShadingSizes(const Scene& scene)
{
  const std::size_t n = scene.positions.size();
  if (scene.normals.size() != n || scene.albedo.size() != n ||
    (!scene.emission.empty() && scene.emission.size() != n))
  {
    fail("The scene's normal, albedo or emission arrays do not have one value per vertex.");
  }
}

/// The errors of albedo, emission, lights and environment (of the arrays not known valid).
void checkShading(const Scene& scene, bool albedoValid = false, bool emissionValid = false)
{
  if (!albedoValid)
  {
    checkArray(scene.albedo, "albedo", negativeOrNotFinite, "a negative or non-finite");
  }
  if (!emissionValid)
  {
    checkArray(scene.emission, "emission", negativeOrTooBright,
      "a negative, non-finite or too large (above 1e30)");
  }
  checkLights(scene.lights);
  const Environment& sky = scene.environment;
  if (negativeOrTooBright(sky.color))
  {
    fail("The environment colour is negative, not finite or above 1e30.");
  }
  if (sky.width < 0 || sky.height < 0 ||
    (!sky.texels.empty() &&
      sky.texels.size() != static_cast<std::size_t>(sky.width) * std::size_t(sky.height)))
  {
    fail("The environment map's texel count does not match its width x height.");
  }
  for (std::size_t i = 0; i < sky.texels.size(); ++i)
  {
    if (negativeOrTooBright(sky.texels[i]))
    {
      fail("Texel " + std::to_string(i) + " of the environment map is negative, not finite or above 1e30.");
    }
  }
}

/// Albedo above 1 (clamped or rejected), and a scene without any light.
void repairShading(Scene& scene, AlbedoPolicy policy, std::vector<std::string>& warnings,
  bool albedoValid = false)
{
  // maxComponent(a) > 1, without libm's fmaxf
  const auto aboveOne = [](const Vec3f& a) { return a.x > 1.f || a.y > 1.f || a.z > 1.f; };
  std::size_t above = 0;
  const std::size_t first = albedoValid ? scene.albedo.size() :
    firstIndexWhere(scene.albedo.size(), kScanGrain, [&](std::size_t i) { return aboveOne(scene.albedo[i]); });
  for (std::size_t i = first; i < scene.albedo.size(); ++i)
  {
    Vec3f& a = scene.albedo[i];
    if (aboveOne(a))
    {
      ++above;
      a = { std::min(a.x, 1.f), std::min(a.y, 1.f), std::min(a.z, 1.f) };
    }
  }
  if (above > 0)
  {
    if (policy == AlbedoPolicy::Reject)
    {
      fail(std::to_string(above) +
        " vertices have an albedo above 1, which would create energy; scale the albedo to [0,1].");
    }
    warnings.push_back("Clamped the albedo of " + std::to_string(above) +
      " vertices to 1: an albedo above 1 would create energy.");
  }

  bool anyLight = false;
  for (const Light& l : scene.lights)
  {
    anyLight = anyLight || maxComponent(l.intensity) > 0.f;
  }
  // The emission is scanned only when no light shines.
  const auto anyEmission = [&scene] {
    return std::any_of(scene.emission.begin(), scene.emission.end(),
      [](const Vec3f& e) { return e.x > 0.f || e.y > 0.f || e.z > 0.f; });
  };
  if (!anyLight && scene.environment.isBlack() && !anyEmission())
  {
    warnings.push_back("The scene has no lights, no emission and a black environment: "
                       "all irradiance is zero.");
  }
}
}

bool validateChanges(Scene& scene, AlbedoPolicy policy, const KnownValid& known, std::vector<std::string>& warnings)
{
  warnings.clear();
  const std::size_t n = scene.positions.size();
  if (n == 0)
  {
    fail("The scene has no vertices.");
  }
  if (scene.triangles.empty())
  {
    fail("The scene has no triangles: global illumination needs surfaces (polygons or strips).");
  }
  checkShadingSizes(scene);
  const std::vector<Triangle>& triangles = scene.triangles;
  const std::size_t outside = known.triangles ? triangles.size() :
    firstIndexWhere(triangles.size(), kScanGrain,
      [&](std::size_t i) { return triangles[i].v[0] >= n || triangles[i].v[1] >= n || triangles[i].v[2] >= n; });
  if (outside < triangles.size())
  {
    const Triangle& t = triangles[outside];
    const Index v = t.v[0] >= n ? t.v[0] : t.v[1] >= n ? t.v[1] : t.v[2];
    fail("Triangle " + std::to_string(outside) + " refers to vertex " + std::to_string(v) +
      ", but the scene has only " + std::to_string(n) + " vertices.");
  }
  if (!known.positions)
  {
    checkArray(scene.positions, "position", notFinite, "a non-finite (NaN or Inf)");
  }
  if (!known.normals)
  {
    checkArray(scene.normals, "normal", notFinite, "a non-finite (NaN or Inf)");
  }
  checkShading(scene, known.albedo, known.emission);
  checkMaterials(scene);
  if (!known.positions)
  {
    normalizeLength(scene);
  }
  scaleLights(scene.lights, scene.lengthExponent);

  // Valid triangles on valid positions have no degenerate one.
  const std::size_t degenerate = known.triangles && known.positions ? triangles.size() : firstDegenerateTriangle(scene);
  if (degenerate < triangles.size())
  {
    if (known.triangles)
    {
      return false; // the moved positions made a triangle degenerate: the caller's copy goes
    }
    warnings.push_back(
      "Removed " + std::to_string(removeDegenerateTriangles(scene, degenerate)) + " degenerate triangles.");
    if (scene.triangles.empty())
    {
      fail("Every triangle of the scene is degenerate (zero area).");
    }
  }
  if (!known.normals)
  {
    if (const std::size_t repaired = repairNormals(scene))
    {
      warnings.push_back(
        "Replaced " + std::to_string(repaired) + " zero-length normals by face normals.");
    }
  }
  repairShading(scene, policy, warnings, known.albedo);
  return true;
}

std::vector<std::string> validateScene(Scene& scene, AlbedoPolicy policy)
{
  std::vector<std::string> warnings;
  validateChanges(scene, policy, KnownValid{}, warnings);
  return warnings;
}

std::vector<std::string> validateShading(
  Scene& scene, AlbedoPolicy policy, bool albedoValidated, bool emissionValidated)
{
  KnownValid known;
  known.positions = known.normals = known.triangles = true;
  known.albedo = albedoValidated;
  known.emission = emissionValidated;
  std::vector<std::string> warnings;
  validateChanges(scene, policy, known, warnings);
  return warnings;
}

bool Scene::hasSpecular() const
{
  return std::any_of(triangleMaterials.begin(), triangleMaterials.end(),
    [](MaterialType m) { return m != MaterialType::Diffuse; });
}
}
