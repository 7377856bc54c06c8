// What every fuzz target builds from its bytes: sizes, numbers of any bit pattern, engine
// scenes, lights and options. Sizes are small (a few dozen elements), so that a run tries
// many inputs per second; sizes that disagree with each other are what validation is for.
#pragma once

#include "linkgi/Scene.h"
#include "linkgi/SolverTypes.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

/// A property every accepted input must have: a violation is reported as a crash, with the
/// property's text.
#define LINKGI_FUZZ_REQUIRE(condition)                                                       \
  do                                                                                         \
  {                                                                                          \
    if (!(condition))                                                                        \
    {                                                                                        \
      std::fprintf(stderr, "%s:%d: %s does not hold\n", __FILE__, __LINE__, #condition);   \
      std::abort();                                                                          \
    }                                                                                        \
  } while (false)

namespace linkgi_fuzz
{
class Input
{
public:
  Input(const std::uint8_t* data, std::size_t size) : provider(data, size) {}

  bool boolean() { return provider.ConsumeBool(); }
  /// 0..max, small values most often.
  std::size_t count(std::size_t max) { return provider.ConsumeIntegralInRange<std::size_t>(0, max); }
  template <typename T>
  T integer()
  {
    return provider.ConsumeIntegral<T>();
  }
  template <typename T>
  T pick(std::initializer_list<T> values)
  {
    return provider.PickValueInArray(values);
  }
  /// A float: half the time one of the values at the edges, else any bit pattern.
  float number()
  {
    constexpr float inf = std::numeric_limits<float>::infinity();
    if (provider.ConsumeBool())
    {
      return provider.PickValueInArray({ 0.f, -0.f, 1.f, -1.f, 0.5f, 2.f, 1e-30f, 1e30f, -1e30f,
        3.4e38f, -3.4e38f, 1e-45f, inf, -inf, std::numeric_limits<float>::quiet_NaN() });
    }
    const std::uint32_t bits = provider.ConsumeIntegral<std::uint32_t>();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
  double real()
  {
    return provider.ConsumeBool() ? double(number()) : provider.ConsumeFloatingPoint<double>();
  }

private:
  FuzzedDataProvider provider;
};

inline linkgi::Vec3f vector(Input& in)
{
  const float x = in.number(), y = in.number();
  return linkgi::Vec3f(x, y, in.number());
}

inline std::vector<linkgi::Vec3f> vectors(Input& in, std::size_t n)
{
  std::vector<linkgi::Vec3f> v(n);
  for (linkgi::Vec3f& x : v)
  {
    x = vector(in);
  }
  return v;
}

/// Sizes of `nominal` most of the time, any other small size sometimes.
inline std::size_t sizeNear(Input& in, std::size_t nominal)
{
  return in.count(7) == 0 ? in.count(2 * nominal + 2) : nominal;
}

inline std::vector<linkgi::Light> lights(Input& in)
{
  std::vector<linkgi::Light> lights(in.count(3));
  for (linkgi::Light& l : lights)
  {
    l.type = linkgi::LightType(in.count(3)); // 3: not a light type
    l.position = vector(in);
    l.direction = vector(in);
    l.intensity = vector(in);
    l.coneAngleDegrees = in.number();
    l.spotExponent = in.number();
  }
  return lights;
}

/// A scene of up to 32 vertices and 48 triangles, its arrays of any size and content.
inline linkgi::Scene scene(Input& in)
{
  linkgi::Scene s;
  const std::size_t n = in.count(32);
  s.positions = vectors(in, n);
  s.normals = vectors(in, sizeNear(in, n));
  s.albedo = vectors(in, sizeNear(in, n));
  if (in.boolean())
  {
    s.emission = vectors(in, sizeNear(in, n));
  }
  s.triangles.resize(in.count(48));
  for (linkgi::Triangle& t : s.triangles)
  {
    for (linkgi::Index& v : t.v)
    {
      // Mostly in range; sometimes anything.
      v = in.count(15) ? linkgi::Index(in.count(n ? n - 1 : 0)) : in.integer<linkgi::Index>();
    }
  }
  s.lights = lights(in);
  s.environment.color = vector(in);
  if (in.boolean())
  {
    s.environment.width = in.integer<std::int8_t>();
    s.environment.height = in.integer<std::int8_t>();
    const int w = s.environment.width > 0 ? s.environment.width : 0;
    const int h = s.environment.height > 0 ? s.environment.height : 0;
    s.environment.texels = vectors(in, sizeNear(in, std::size_t(w) * std::size_t(h)));
  }
  return s;
}
}
