// Scene arrays: the engine's input, independent of VTK.
#pragma once

#include "linkgi/Math.h"

#include <cstring>
#include <string>
#include <vector>

namespace linkgi
{
struct Triangle
{
  Index v[3];
};

enum class LightType : std::uint32_t
{
  Point = 0,       ///< isotropic, `intensity` in W/sr
  Spot = 1,        ///< point light restricted to a cone around `direction`
  Directional = 2, ///< parallel light travelling along `direction`, `intensity` in W/m^2
};

/// One light. Plain data: the same struct is read by the CPU and the GPU backends.
struct Light
{
  LightType type = LightType::Point;
  Vec3f position{ 0.f, 0.f, 0.f };
  /// Direction the light travels (spot axis, or the directional light's rays); unit length.
  Vec3f direction{ 0.f, 0.f, -1.f };
  /// Linear RGB, HDR allowed. Point and spot: radiant intensity (W/sr), so a surface at
  /// distance r facing the light receives intensity / r^2. Directional: irradiance on a
  /// surface perpendicular to the light.
  Vec3f intensity{ 1.f, 1.f, 1.f };
  /// Spot only: half angle of the cone, in degrees.
  float coneAngleDegrees = 30.f;
  /// Spot only: cos(angle to axis)^exponent falloff inside the cone (0 = hard cone).
  float spotExponent = 0.f;
  /// Point and spot: distance falloff (constant c, linear l, quadratic q, vtkLight's
  /// AttenuationValues): a surface at distance r facing the light receives
  /// intensity / (c + l r + q r^2). The default (0, 0, 1) is a physical lamp's 1/r^2.
  Vec3f attenuation{ 0.f, 0.f, 1.f };
};

/// Texel of a width x height lat-long map seen along the unit direction d (layout below);
/// the one formula the CPU and the GPU both use.
LINKGI_HOST_DEVICE inline Index environmentTexel(int width, int height, const Vec3f& d)
{
  const float u = std::atan2(d.x, -d.z) * (0.5f / kPi) + 0.5f;
  const float v = std::acos(fminf(fmaxf(d.y, -1.f), 1.f)) / kPi;
  const int col = static_cast<int>(fminf(fmaxf(u * width, 0.f), float(width - 1)));
  const int row = static_cast<int>(fminf(fmaxf(v * height, 0.f), float(height - 1)));
  return Index(row) * Index(width) + Index(col);
}

/// Radiance arriving from infinity along directions that hit no geometry.
/// A constant colour, optionally modulated by a lat-long (equirectangular) map with +Y up:
/// column u = (atan2(d.x, -d.z) / 2pi + 1/2) * width, row v = acos(d.y) / pi * height.
struct Environment
{
  Vec3f color{ 0.f, 0.f, 0.f };
  int width = 0;
  int height = 0;
  std::vector<Vec3f> texels; ///< width * height RGB radiance values, row 0 at +Y

  bool isBlack() const;
  bool hasTexture() const { return width > 0 && height > 0 && !texels.empty(); }
  /// Texel seen along the unit direction `d` (0 without a texture).
  Index texelIndex(const Vec3f& d) const;
  /// Radiance seen along the unit direction `d` (from the surface towards the sky).
  Vec3f radiance(const Vec3f& d) const;
};

/// How a triangle scatters light. Only Method::PhotonMapping and the reference carry light
/// through mirrors and glass; the other methods light them as diffuse surfaces (warned).
enum class MaterialType : std::uint8_t
{
  Diffuse = 0, ///< Lambertian, the vertices' albedo
  Mirror = 1,  ///< perfect specular reflection
  Glass = 2    ///< smooth dielectric: Fresnel reflection and refraction (Scene::triangleIor)
};

/// A triangle mesh with per-vertex shading data and lights.
/// Vertices are the elements of the solution: a vertex shared by triangles with different
/// normals (a sharp edge) must be split by the caller into one vertex per side.
struct Scene
{
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;  ///< unit length, one per vertex, pointing to the lit side
  std::vector<Vec3f> albedo;   ///< diffuse reflectance rho per vertex, each channel in [0,1]
  std::vector<Vec3f> emission; ///< emitted radiance Le per vertex (empty = none)
  std::vector<Triangle> triangles;
  /// One per triangle, or empty for all diffuse.
  std::vector<MaterialType> triangleMaterials;
  /// Glass: index of refraction per triangle (> 0, finite), or empty for 1.5.
  std::vector<float> triangleIor;
  std::vector<Light> lights;
  Environment environment;
  /// 0 in an input. validateScene sets it for a scene far from unit size (outside 2^-16 to
  /// 2^16): the validated positions and light positions are multiplied by 2^-lengthExponent
  /// and point and spot intensities by 4^-lengthExponent (exact powers of two), so that ray
  /// tests and 1/r^2 stay within single precision for a mesh of size 1e30 or 1e-30. The
  /// irradiance and radiance of the solution are unchanged by it.
  int lengthExponent = 0;

  std::size_t vertexCount() const { return positions.size(); }
  /// Whether any triangle is a mirror or glass.
  bool hasSpecular() const;
  MaterialType material(std::size_t triangle) const
  {
    return triangleMaterials.empty() ? MaterialType::Diffuse : triangleMaterials[triangle];
  }
  float ior(std::size_t triangle) const { return triangleIor.empty() ? 1.5f : triangleIor[triangle]; }
  std::size_t triangleCount() const { return triangles.size(); }
};

/// What validateScene does with albedo above 1 (physically, energy would be created).
enum class AlbedoPolicy
{
  Clamp, ///< clamp each channel to [0,1] and report it in the returned warnings (default)
  Reject ///< throw linkgi::Error
};

/// Checks a scene before solving and repairs what can be repaired, so that the solver never
/// sees NaNs or out-of-range data. Throws linkgi::Error with a sentence naming the problem for:
/// no vertices, no triangles, index out of range, array sizes that disagree (materials and
/// indices of refraction: one per triangle), an unknown material, an index of refraction not
/// above 0 or not finite, non-finite
/// positions/normals/albedo/emission/light data, negative albedo, emission, light or
/// environment, emission or environment above 1e30 (the bounces would overflow), a point or
/// spot light too far away for the rescaled scene (below).
/// Repairs (each listed in the returned warnings): degenerate triangles (zero area or repeated
/// indices) are removed; zero-length normals are replaced by the area-weighted face normal;
/// normals and light directions of any other length are made unit length (not warned);
/// albedo above 1 is clamped (AlbedoPolicy::Clamp). A scene far from unit size is rescaled
/// by a power of two (see Scene::lengthExponent), which changes no result. A scene with no lights and a black
/// environment and no emission is valid: its solution is all zero (warned).
std::vector<std::string> validateScene(Scene& scene, AlbedoPolicy policy = AlbedoPolicy::Clamp);

/// Which arrays of a scene are known to have passed validateScene unchanged, in a scene of
/// the same vertex count (the arrays the solver lends from its last update).
struct KnownValid
{
  bool positions = false; ///< with the lengthExponent they were rescaled by
  bool normals = false;
  bool triangles = false;
  bool albedo = false;
  bool emission = false;
};

/// validateScene for a scene whose `known` arrays passed it unchanged before: the same
/// errors, repairs and warnings (into `warnings`), from scans of the other arrays only, so a
/// deformation scans the positions and a light move no array of the mesh. Known arrays are
/// never changed: where moved positions make a triangle of known triangles degenerate, it
/// returns false, and the scene is to be validated again with triangles not known.
bool validateChanges(Scene& scene, AlbedoPolicy policy, const KnownValid& known, std::vector<std::string>& warnings);

/// validateChanges for a scene whose positions, normals and triangles passed validateScene
/// unchanged before (light and material updates); `albedoValidated` / `emissionValidated`:
/// that array too.
std::vector<std::string> validateShading(Scene& scene, AlbedoPolicy policy = AlbedoPolicy::Clamp,
  bool albedoValidated = false, bool emissionValidated = false);

/// Bitwise equality of two arrays, on one thread (the solver compares a large mesh's arrays
/// on all cores: on an H200 machine's 16-core host 0.16-0.17 ms for four of conference's
/// arrays against 0.34-0.41 ms on one).
template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), sizeof(T) * a.size()) == 0);
}

/// True if every array, light and the environment of `a` and `b` are bitwise equal.
bool sameScene(const Scene& a, const Scene& b);

/// The axis-aligned box of `positions` (lo = hi = 0 for none), on all cores.
void positionBounds(const std::vector<Vec3f>& positions, Vec3f& lo, Vec3f& hi);

/// The diagonal of the box [lo, hi], in double (no overflow for coordinates near the float
/// limit).
float boxDiagonal(const Vec3f& lo, const Vec3f& hi);

/// Axis-aligned bounding box diagonal length (used to scale ray offsets), computed in double
/// (no overflow for coordinates near the float limit).
float boundingDiagonal(const std::vector<Vec3f>& positions);
}
