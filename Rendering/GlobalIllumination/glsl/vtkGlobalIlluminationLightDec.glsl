// LinkGI (vtkGlobalIlluminationMapper): direct light with shadow maps plus per-vertex
// indirect light, in linear RGB and world coordinates. #defined before this text:
// GI_LIGHT_COUNT, GI_HAS_ALBEDO, GI_HAS_INDIRECT, GI_HAS_EMISSION, GI_GLOSSY,
// GI_MODE (0 combined, 1 direct, 2 indirect), GI_TONE_MAPPING (0 linear, 1 exponential,
// 2 Reinhard).
#define GI_PI 3.14159265358979

uniform mat4 giViewToWorld;
uniform vec4 giCamera; // w = 0: eye position; w = 1: unit direction towards the eye
uniform float giExposure;
uniform float giInvGamma;
uniform sampler2DArrayShadow giShadowMaps;
uniform vec3 giShadowFilter; // 1 / resolution, filter radius (texels), bias (texels)

#if GI_HAS_ALBEDO
in vec4 giAlbedoVSOutput;
#endif
#if GI_HAS_INDIRECT
in vec3 giIndirectVSOutput;
#endif
#if GI_HAS_EMISSION
in vec3 giEmissionVSOutput;
#endif

#if GI_LIGHT_COUNT > 0
uniform int giLightType[GI_LIGHT_COUNT];      // 0 point, 1 spot, 2 directional
uniform vec3 giLightPosition[GI_LIGHT_COUNT];
uniform vec3 giLightDirection[GI_LIGHT_COUNT]; // unit direction of travel (spot axis)
uniform vec3 giLightIntensity[GI_LIGHT_COUNT]; // W/sr (point, spot), W/m^2 (directional)
uniform vec2 giLightCone[GI_LIGHT_COUNT];      // cos(cone angle), spot exponent
uniform int giShadowKind[GI_LIGHT_COUNT];  // 0 none, 1 cube, 2 perspective, 3 orthographic
uniform int giShadowLayer[GI_LIGHT_COUNT]; // first layer in giShadowMaps
uniform mat4 giShadowMatrix[GI_LIGHT_COUNT]; // world to clip (kinds 2 and 3)
uniform vec4 giShadowDepth[GI_LIGHT_COUNT];  // depth scale, offset; texel = z * distance + w

// Cube faces in the layer order +X -X +Y -Y +Z -Z, and the image axes u, v of each face:
// a direction d shows at (d.u, d.v) / |d|_max. The shadow-map renderer uses the same table.
const vec3 giFaceU[6] = vec3[6](vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0),
  vec3(1.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0), vec3(-1.0, 0.0, 0.0));
const vec3 giFaceV[6] = vec3[6](vec3(0.0, -1.0, 0.0), vec3(0.0, -1.0, 0.0), vec3(0.0, 0.0, 1.0),
  vec3(0.0, 0.0, -1.0), vec3(0.0, -1.0, 0.0), vec3(0.0, -1.0, 0.0));

int giCubeFace(vec3 d)
{
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z)
  {
    return d.x > 0.0 ? 0 : 1;
  }
  if (a.y >= a.z)
  {
    return d.y > 0.0 ? 2 : 3;
  }
  return d.z > 0.0 ? 4 : 5;
}

// One bilinear depth comparison (1 = lit). Every tap picks its own face, so filters that
// straddle a cube edge need no seam handling.
float giCubeTap(float layer, vec3 d, float depth)
{
  int f = giCubeFace(d);
  float major = max(max(abs(d.x), abs(d.y)), abs(d.z));
  vec2 uv = vec2(dot(d, giFaceU[f]), dot(d, giFaceV[f])) / major;
  return texture(giShadowMaps, vec4(0.5 * uv + 0.5, layer + float(f), depth));
}

// Percentage-closer filter over a (2 radius)^2 texel square. Four inner taps decide lit or
// shadowed areas; only penumbrae pay for the eight outer ones.
float giCubeShadow(float layer, vec3 d, float depth)
{
  int f = giCubeFace(d);
  float major = max(max(abs(d.x), abs(d.y)), abs(d.z));
  float texel = 2.0 * giShadowFilter.x * major;
  vec3 du = giFaceU[f] * (texel * giShadowFilter.y), dv = giFaceV[f] * (texel * giShadowFilter.y);
  float s = giCubeTap(layer, d + 0.5 * (du + dv), depth) + giCubeTap(layer, d + 0.5 * (du - dv), depth)
    + giCubeTap(layer, d - 0.5 * (du + dv), depth) + giCubeTap(layer, d - 0.5 * (du - dv), depth);
  if (s == 0.0 || s == 4.0)
  {
    return 0.25 * s;
  }
  s += giCubeTap(layer, d + du, depth) + giCubeTap(layer, d - du, depth)
    + giCubeTap(layer, d + dv, depth) + giCubeTap(layer, d - dv, depth)
    + giCubeTap(layer, d + du + dv, depth) + giCubeTap(layer, d + du - dv, depth)
    + giCubeTap(layer, d - du + dv, depth) + giCubeTap(layer, d - du - dv, depth);
  return s / 12.0;
}

float giImageTap(float layer, vec2 uv, float depth)
{
  return texture(giShadowMaps, vec4(uv, layer, depth));
}

// The same filter in a 2D layer (spot and directional lights).
float giImageShadow(float layer, vec2 uv, float depth)
{
  vec2 du = vec2(giShadowFilter.x * giShadowFilter.y, 0.0), dv = du.yx;
  float s = giImageTap(layer, uv + 0.5 * (du + dv), depth) + giImageTap(layer, uv + 0.5 * (du - dv), depth)
    + giImageTap(layer, uv - 0.5 * (du + dv), depth) + giImageTap(layer, uv - 0.5 * (du - dv), depth);
  if (s == 0.0 || s == 4.0)
  {
    return 0.25 * s;
  }
  s += giImageTap(layer, uv + du, depth) + giImageTap(layer, uv - du, depth)
    + giImageTap(layer, uv + dv, depth) + giImageTap(layer, uv - dv, depth)
    + giImageTap(layer, uv + du + dv, depth) + giImageTap(layer, uv + du - dv, depth)
    + giImageTap(layer, uv - du + dv, depth) + giImageTap(layer, uv - du - dv, depth);
  return s / 12.0;
}

// Filtered shadow-map lookup of light i at q (1 = lit).
float giShadowLookup(int i, vec3 q)
{
  vec4 sd = giShadowDepth[i];
  float layer = float(giShadowLayer[i]);
  if (giShadowKind[i] == 1)
  {
    vec3 d = q - giLightPosition[i];
    return giCubeShadow(layer, d, length(d) * sd.x + sd.y);
  }
  vec4 clip = giShadowMatrix[i] * vec4(q, 1.0);
  vec2 uv = 0.5 * clip.xy / clip.w + 0.5;
  if (clip.w <= 0.0 || any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
  {
    return 1.0; // outside the map: nothing there casts shadows
  }
  float x = giShadowKind[i] == 2 ? length(q - giLightPosition[i]) : dot(q, giLightDirection[i]);
  return giImageShadow(layer, uv, x * sd.x + sd.y);
}

// Fraction of light i that reaches p, at distance dist, on a triangle of unit normal g
// (the geometric normal: the shadow map holds the triangles, not the smooth surface that
// the shading normals describe).
//
// Normal-offset bias: the lookup point moves off the triangle by
// bias * (0.5 + sqrt(2) (radius / 2 + 1) sin(theta)) texels, theta the light's angle to
// the triangle. The filter's inner taps reach radius / 2 texels along both axes, plus the
// hardware's bilinear texel, so up to sqrt(2) (radius / 2 + 1) texels along the triangle's
// slope, over which its stored depth changes by that many texels times tan(theta); an
// offset along the normal buys 1 / cos(theta) of depth margin per unit. So the default bias
// of 1 keeps lit surfaces free of acne at any angle, while shadows still start at their
// casters' base (the offset moves the lookup sideways by at most ~3 texels).
//
// Shadow terminator: near the light's terminator on a coarse curved mesh, triangles turn
// away from the light while their smooth shading normals still face it. The triangles
// themselves would shadow such points (black facets, or stripes); the smooth surface
// would not, and neither do the filter's shadow rays, which start along the vertex
// normals. So the shadow fades out as the triangle turns edge-on to the light (over the
// last ~6 degrees); those points are dim anyway, their shading normal being near the
// terminator too.
float giShadowFactor(int i, vec3 p, vec3 g, vec3 l, float dist)
{
  float cosTriangle = dot(g, l);
  if (cosTriangle <= 0.0)
  {
    return 1.0;
  }
  vec4 sd = giShadowDepth[i];
  float texel = sd.z * dist + sd.w;
  float sinTriangle = sqrt(max(1.0 - cosTriangle * cosTriangle, 0.0));
  float offset = 0.5 + 1.41421 * (0.5 * giShadowFilter.y + 1.0) * sinTriangle;
  vec3 q = p + g * (texel * giShadowFilter.z * offset);
  return mix(1.0, giShadowLookup(i, q), smoothstep(0.0, 0.1, cosTriangle));
}
#endif

// Irradiance E_d at p (unit shading normal n, geometric normal g) from all lights, with
// shadows, as linkgi::unshadowedIrradiance computes it; `glossy` collects
// E * (m + 8) / (8 pi) * (n.h)^m, the normalized Blinn-Phong lobe of exponent
// m = specularPower.
vec3 giDirectIrradiance(vec3 p, vec3 n, vec3 g, vec3 eye, float shininess, out vec3 glossy)
{
  vec3 irradiance = vec3(0.0);
  glossy = vec3(0.0);
#if GI_LIGHT_COUNT > 0
  for (int i = 0; i < GI_LIGHT_COUNT; ++i)
  {
    vec3 toLight = giLightType[i] == 2 ? -giLightDirection[i] : giLightPosition[i] - p;
    float dist = length(toLight);
    vec3 l = toLight / dist;
    float cosSurface = dot(n, l);
    if (cosSurface <= 0.0)
    {
      continue;
    }
    vec3 e = giLightIntensity[i] * cosSurface;
    if (giLightType[i] != 2)
    {
      e /= dist * dist;
      if (giLightType[i] == 1)
      {
        float cosAxis = dot(-l, giLightDirection[i]);
        if (cosAxis < giLightCone[i].x)
        {
          continue;
        }
        if (giLightCone[i].y > 0.0)
        {
          e *= pow(max(cosAxis, 0.0), giLightCone[i].y);
        }
      }
    }
    if (giShadowKind[i] != 0)
    {
      e *= giShadowFactor(i, p, g, l, dist);
    }
    irradiance += e;
#if GI_GLOSSY
    vec3 h = normalize(l + eye);
    glossy += e * ((shininess + 8.0) / (8.0 * GI_PI) * pow(max(dot(n, h), 0.0), shininess));
#endif
  }
#endif
  return irradiance;
}

vec3 giToneMap(vec3 radiance)
{
  vec3 x = max(radiance * giExposure, vec3(0.0));
#if GI_TONE_MAPPING == 1
  x = vec3(1.0) - exp(-x);
#elif GI_TONE_MAPPING == 2
  x = x / (vec3(1.0) + x);
#endif
  return pow(x, vec3(giInvGamma));
}
