#include "BenchScenes.h"

#include "scene/MeshBuilder.h"
#include "linkgi/Scenes.h"

#include <cmath>

namespace linkgi::bench
{
namespace
{
Scene isosurface(double vertices)
{
  // 1400 x 740 gives about 1.05M vertices; other sizes scale both directions alike.
  const double f = std::sqrt(vertices / 1.05e6);
  MeshBuilder b;
  b.addBox({ -3, 0, -3 }, { 3, 3, 3 }, 0.1f, Vec3f(0.7f, 0.7f, 0.68f), true);
  const Vec3f c(0.f, 1.3f, 0.f);
  const auto radius = [](float theta, float phi) {
    return 0.8f * (1.f + 0.18f * std::sin(5.f * theta) * std::sin(4.f * phi) +
                    0.07f * std::cos(11.f * theta + 2.f * phi));
  };
  // u around the vertical axis, v from the top pole to the bottom pole.
  b.addSurface(
    [&](float u, float v) {
      const float phi = 2.f * kPi * u, theta = kPi * v;
      const float r = radius(theta, phi);
      return c + Vec3f(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)) * r;
    },
    int(std::lround(1400 * f)), int(std::lround(740 * f)), SurfaceTopology::closed(), Vec3f(0.8f, 0.45f, 0.3f));
  Scene s = b.take();
  for (const Vec3f& p : { Vec3f(1.8f, 2.7f, 1.5f), Vec3f(-2.f, 2.6f, -1.2f) })
  {
    Light l;
    l.position = p;
    l.intensity = Vec3f(6.f, 5.6f, 5.f);
    s.lights.push_back(l);
  }
  return s;
}
}

Scene makeScene(const std::string& name)
{
  if (name == "isosurface")
  {
    return isosurface(1.05e6);
  }
  if (name.rfind("isosurface:", 0) == 0)
  {
    return isosurface(std::stod(name.substr(11)));
  }
  return makeStandardScene(name);
}
}
