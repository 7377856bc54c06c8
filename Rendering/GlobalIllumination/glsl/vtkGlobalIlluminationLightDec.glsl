// LinkGI (vtkGlobalIlluminationMapper): direct light with shadow maps plus per-vertex
// indirect light, in linear RGB and world coordinates. #defined before this text:
// GI_LIGHT_COUNT, GI_HAS_ALBEDO, GI_HAS_INDIRECT, GI_HAS_INDIRECT_BACK, GI_HAS_EMISSION,
// GI_GLOSSY, GI_MODE (0 combined, 1 direct, 2 indirect), GI_TONE_MAPPING (0 linear,
// 1 exponential, 2 Reinhard, 3 hue preserving), GI_SOFT_SHADOWS (four filter taps instead
// of one), and, with lights, GI_LIGHT_TYPES and GI_SHADOW_KINDS (one integer per light).
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
#if GI_HAS_INDIRECT_BACK
in vec3 giIndirectBackVSOutput;
#endif
#if GI_HAS_EMISSION
in vec3 giEmissionVSOutput;
#endif

#if GI_LIGHT_COUNT > 0
// Light types (0 point, 1 spot, 2 directional) and shadow map kinds (0 none, 1 cube,
// 2 perspective, 3 orthographic) are compiled in: they change rarely, and the unrolled
// light loop then holds only the code each light needs.
const int giLightType[GI_LIGHT_COUNT] = int[GI_LIGHT_COUNT](GI_LIGHT_TYPES);
const int giShadowKind[GI_LIGHT_COUNT] = int[GI_LIGHT_COUNT](GI_SHADOW_KINDS);
uniform vec3 giLightPosition[GI_LIGHT_COUNT];
uniform vec3 giLightDirection[GI_LIGHT_COUNT]; // unit direction of travel (spot axis)
uniform vec3 giLightIntensity[GI_LIGHT_COUNT]; // W/sr (point, spot), W/m^2 (directional)
uniform vec2 giLightCone[GI_LIGHT_COUNT];      // cos(cone angle), spot exponent
uniform vec3 giLightAttenuation[GI_LIGHT_COUNT]; // c, l, q: falloff 1 / (c + l r + q r^2)
uniform int giShadowLayer[GI_LIGHT_COUNT]; // first layer in giShadowMaps
uniform mat4 giShadowMatrix[GI_LIGHT_COUNT]; // world to clip (kinds 2 and 3)
uniform vec4 giShadowDepth[GI_LIGHT_COUNT];  // depth scale, offset; texel = z * distance + w

// Shadow-map coordinates (u, v, layer) of the direction d from a point light, its cube
// map starting at `layer`. Faces in the layer order +X -X +Y -Y +Z -Z; a direction shows
// on its major axis' face at (d.u, d.v) / |d|_max with the image axes u, v of
// vtkGlobalIlluminationShadowMaps.cxx (FaceU, FaceV). Written without branches: software
// rasterizers (Mesa llvmpipe) run both sides of a branch under a mask.
vec3 giCubeCoordinates(vec3 d, float layer)
{
  vec3 a = abs(d);
  vec3 s = sign(d);
  bool xMajor = a.x >= a.y && a.x >= a.z;
  bool yMajor = !xMajor && a.y >= a.z;
  vec2 uv = xMajor ? vec2(-s.x * d.z, -d.y) / a.x
                   : (yMajor ? vec2(d.x, s.y * d.z) / a.y : vec2(s.z * d.x, -d.y) / a.z);
  float face = xMajor ? 0.5 - 0.5 * s.x : (yMajor ? 2.5 - 0.5 * s.y : 4.5 - 0.5 * s.z);
  return vec3(0.5 * uv + 0.5, layer + face);
}

// Percentage-closer filter (1 = lit). The hardware's bilinear depth comparison blends the
// 2 x 2 nearest texels, which smooths aliased edges; with GI_SOFT_SHADOWS, four such taps
// at +-radius / 2 texels make a tent over radius + 2 texels for wider, softer edges (at
// four times the texture cost, which dominates on software rasterizers). Cube faces are
// not crossed: near a cube edge the taps clamp to the face.
float giFilteredShadow(vec3 coordinates, float depth)
{
#if GI_SOFT_SHADOWS
  float h = 0.5 * giShadowFilter.y * giShadowFilter.x;
  return 0.25 *
    (texture(giShadowMaps, vec4(coordinates.xy + vec2(-h, -h), coordinates.z, depth)) +
      texture(giShadowMaps, vec4(coordinates.xy + vec2(h, -h), coordinates.z, depth)) +
      texture(giShadowMaps, vec4(coordinates.xy + vec2(-h, h), coordinates.z, depth)) +
      texture(giShadowMaps, vec4(coordinates.xy + vec2(h, h), coordinates.z, depth)));
#else
  return texture(giShadowMaps, vec4(coordinates, depth));
#endif
}

// Fraction of light i that reaches p, at distance dist, on a triangle of unit normal g
// (the geometric normal: the shadow map holds the triangles, not the smooth surface that
// the shading normals describe); l is the unit direction to the light.
//
// Normal-offset bias: the lookup point moves off the triangle by
// bias * (0.5 + sqrt(2) (radius / 2 + 1) sin(theta)) texels, theta the light's angle to
// the triangle. The filter's taps reach radius / 2 texels along both axes, plus the
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
  vec4 sd = giShadowDepth[i];
  int kind = giShadowKind[i];
  float cosTriangle = dot(g, l);
  float sinTriangle = sqrt(max(1.0 - cosTriangle * cosTriangle, 0.0));
  float texel = sd.z * dist + sd.w;
  float offset = 0.5 + 1.41421 * (0.5 * giShadowFilter.y + 1.0) * sinTriangle;
  vec3 q = p + g * (texel * giShadowFilter.z * offset);
  vec3 fromLight = q - giLightPosition[i];
  // Cube map (kind 1) or 2D map (2: perspective, 3: orthographic), chosen without branches.
  vec4 clip = giShadowMatrix[i] * vec4(q, 1.0);
  vec3 image = vec3(0.5 * clip.xy / clip.w + 0.5, float(giShadowLayer[i]));
  vec3 coordinates = kind == 1 ? giCubeCoordinates(fromLight, image.z) : image;
  float x = kind == 3 ? dot(q, giLightDirection[i]) : length(fromLight);
  float lit = giFilteredShadow(coordinates, x * sd.x + sd.y);
  // Outside a 2D map nothing casts shadows.
  bool inside = kind == 1 ||
    (clip.w > 0.0 && all(greaterThanEqual(image.xy, vec2(0.0))) &&
      all(lessThanEqual(image.xy, vec2(1.0))));
  lit = inside ? lit : 1.0;
  return mix(1.0, lit, smoothstep(0.0, 0.1, cosTriangle) * float(kind != 0));
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
    bool directional = giLightType[i] == 2;
    vec3 toLight = directional ? -giLightDirection[i] : giLightPosition[i] - p;
    float dist = length(toLight);
    vec3 l = toLight / dist;
    vec3 a = giLightAttenuation[i];
    float falloff = directional ? 1.0 : 1.0 / (a.x + dist * (a.y + a.z * dist));
    float cosAxis = dot(-l, giLightDirection[i]);
    vec2 cone = giLightCone[i];
    float spot = cosAxis < cone.x ? 0.0 : (cone.y > 0.0 ? pow(max(cosAxis, 1e-6), cone.y) : 1.0);
    falloff *= giLightType[i] == 1 ? spot : 1.0;
    vec3 e = giLightIntensity[i] * (max(dot(n, l), 0.0) * falloff);
    e *= giShadowFactor(i, p, g, l, dist);
    irradiance += e;
#if GI_GLOSSY
    vec3 h = normalize(l + eye);
    glossy += e * ((shininess + 8.0) / (8.0 * GI_PI) * pow(max(dot(n, h), 0.0), shininess));
#endif
  }
#endif
  return irradiance;
}

// The sRGB curves of vtkGlobalIlluminationColors (ToLinear, ToDisplay).
vec3 giToLinear(vec3 c)
{
  c = clamp(c, 0.0, 1.0);
  return mix(pow((c + 0.055) / 1.055, vec3(2.4)), c / 12.92, lessThanEqual(c, vec3(0.04045)));
}

vec3 giToDisplay(vec3 c)
{
  c = clamp(c, 0.0, 1.0);
  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}

// The photographic curves: radiance to display values.
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

// Hue-preserving display of a colour c (display units, 1 = white): within [0, 1] it is
// shown as it is. Beyond, its luminance is kept (up to white) and it is blended towards the
// grey of that luminance just enough to fit: hue kept, saturation given up, rather than
// per-channel clipping or compression, which turn a saturated red orange or pink.
vec3 giKeepHue(vec3 c)
{
  c = max(c, vec3(0.0));
  float top = max(c.r, max(c.g, c.b));
  float y = dot(c, vec3(0.2126, 0.7152, 0.0722));
  float grey = min(y, 1.0);
  float keep = top > 1.0 ? clamp((1.0 - grey) / max(top - y, 1e-6), 0.0, 1.0) : 1.0;
  return min(vec3(grey) + (c - vec3(y)) * keep, vec3(1.0));
}
