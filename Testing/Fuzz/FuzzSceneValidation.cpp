// libFuzzer target: validateScene and validateShading on arbitrary arrays of arbitrary
// sizes (floats of any bit pattern: NaN, infinities, denormals, 1e38). Either validation
// throws linkgi::Error, or the scene it leaves is one the solver may trust: sizes that
// agree, indices in range, finite data, albedo in [0, 1], unit normals and light
// directions, no negative light.
#include "FuzzInput.h"

#include "linkgi/Error.h"
#include "linkgi/Scene.h"

#include <cmath>
#include <cstdlib>

using namespace linkgi;

namespace
{
bool finite(const Vec3f& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void checkValidated(const Scene& s)
{
  const std::size_t n = s.vertexCount();
  LINKGI_FUZZ_REQUIRE(n > 0 && s.triangleCount() > 0);
  LINKGI_FUZZ_REQUIRE(s.normals.size() == n && s.albedo.size() == n);
  LINKGI_FUZZ_REQUIRE(s.emission.empty() || s.emission.size() == n);
  for (const Triangle& t : s.triangles)
  {
    LINKGI_FUZZ_REQUIRE(t.v[0] < n && t.v[1] < n && t.v[2] < n);
    LINKGI_FUZZ_REQUIRE(t.v[0] != t.v[1] && t.v[1] != t.v[2] && t.v[0] != t.v[2]);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    LINKGI_FUZZ_REQUIRE(finite(s.positions[i]) && finite(s.normals[i]) && finite(s.albedo[i]));
    const float len = std::sqrt(dot(s.normals[i], s.normals[i]));
    LINKGI_FUZZ_REQUIRE(std::fabs(len - 1.f) < 1e-3f);
    for (float c : { s.albedo[i].x, s.albedo[i].y, s.albedo[i].z })
    {
      LINKGI_FUZZ_REQUIRE(c >= 0.f && c <= 1.f);
    }
  }
  for (const Vec3f& e : s.emission)
  {
    LINKGI_FUZZ_REQUIRE(finite(e) && e.x >= 0.f && e.y >= 0.f && e.z >= 0.f);
  }
  for (const Light& l : s.lights)
  {
    LINKGI_FUZZ_REQUIRE(finite(l.position) && finite(l.direction) && finite(l.intensity));
    LINKGI_FUZZ_REQUIRE(l.intensity.x >= 0.f && l.intensity.y >= 0.f && l.intensity.z >= 0.f);
    LINKGI_FUZZ_REQUIRE(l.type == LightType::Point || std::fabs(length(l.direction) - 1.f) < 1e-3f);
  }
  const Environment& sky = s.environment;
  LINKGI_FUZZ_REQUIRE(finite(sky.color) && sky.color.x >= 0.f && sky.color.y >= 0.f && sky.color.z >= 0.f);
  for (const Vec3f& t : sky.texels)
  {
    LINKGI_FUZZ_REQUIRE(finite(t) && t.x >= 0.f && t.y >= 0.f && t.z >= 0.f);
  }
}
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  linkgi_fuzz::Input in(data, size);
  Scene scene = linkgi_fuzz::scene(in);
  const AlbedoPolicy policy = in.boolean() ? AlbedoPolicy::Clamp : AlbedoPolicy::Reject;
  try
  {
    validateScene(scene, policy);
  }
  catch (const Error&)
  {
    return 0;
  }
  checkValidated(scene);
  // The shading half again on the validated scene with new lights and colours, as a
  // light or material update would: the same guarantees.
  scene.lights = linkgi_fuzz::lights(in);
  if (in.boolean())
  {
    scene.albedo = linkgi_fuzz::vectors(in, scene.vertexCount());
  }
  try
  {
    validateShading(scene, policy);
  }
  catch (const Error&)
  {
    return 0;
  }
  checkValidated(scene);
  return 0;
}
