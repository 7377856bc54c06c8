// Shadow acne and peter-panning at the default bias, for each kind of shadow map.
//
// A unit cube stands on a plane, seen from straight above (parallel projection), lit by
// one light at a time: a directional light, a point light and a spot light, all low over
// the plane on the +x side so that the plane is lit at grazing angles (where acne shows).
// Both filters are checked: the default single bilinear lookup and the soft four-tap one.
// - Acne: on the side of the cube facing the light nothing can be shadowed, so every pixel
//   there must equal the rendering with shadows off.
// - Peter-panning: for the directional light the shadow is known exactly; the plane 2
//   pixels from the cube's base on the shadow side must be dark. The far end of the shadow
//   may move by the filter's half width plus the normal offset (about 2 texels, 1.5 pixels
//   here): 4 pixels inside it must be dark, 4 pixels beyond it lit.
// - Terminator: a coarse sphere (convex, so nothing on it is shadowed) under each light
//   must look the same with and without shadows: its triangles may not shadow the smooth
//   surface their normals describe.
#include "RenderingTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkCubeSource.h"
#include "vtkPlaneSource.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

#include <cmath>

namespace
{
using namespace linkgi_test;

const int Size = 400;          // pixels
const double HalfWidth = 2.5;  // world units shown on each side of the origin
const double Elevation = 30.0; // degrees, of the directional light

vtkSmartPointer<vtkPolyData> CubeOnPlane()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-3, -3, 0);
  plane->SetPoint1(3, -3, 0);
  plane->SetPoint2(-3, 3, 0);
  plane->SetResolution(30, 30);
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(0, 0, 0.5);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputConnection(plane->GetOutputPort());
  append->AddInputConnection(cube->GetOutputPort());
  append->Update();
  return append->GetOutput();
}

vtkSmartPointer<vtkPolyData> CoarseSphere()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.2);
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetThetaResolution(12);
  sphere->SetPhiResolution(8);
  sphere->Update();
  return sphere->GetOutput();
}

vtkSmartPointer<vtkLight> MakeLight(int kind)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  if (kind == 0)
  {
    const double e = vtkMath::RadiansFromDegrees(Elevation);
    light->SetPositional(false);
    light->SetPosition(std::cos(e), 0, std::sin(e));
    light->SetFocalPoint(0, 0, 0);
    light->SetIntensity(1.0);
  }
  else
  {
    light->SetPositional(true);
    light->SetAttenuationValues(0, 0, 1); // a lamp: 1/r^2
    light->SetPosition(2.6, 0.3, 0.7);
    light->SetFocalPoint(0, 0, 0);
    light->SetConeAngle(kind == 1 ? 180.0 : 50.0);
    light->SetIntensity(3.0);
  }
  return light;
}

/// The scene under `light`, with or without shadows: linear output (gamma 1).
vtkSmartPointer<vtkImageData> Render(
  vtkRenderWindow* window, vtkPolyData* scene, vtkLight* light, bool shadows, double filterRadius)
{
  vtkNew<vtkRenderer> renderer;
  renderer->AddLight(light);
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, scene);
  vtkGlobalIlluminationShading* shading = mapper->GetShading();
  shading->SetDisplayModeToDirect();
  shading->SetToneMappingToLinear();
  shading->SetGamma(1.0);
  shading->SetExposure(2.0);
  shading->SetShadows(shadows);
  shading->SetShadowFilterRadius(filterRadius);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(HalfWidth);
  camera->SetPosition(0, 0, 10);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
  return RenderAlone(window, renderer);
}

int ToPixel(double world)
{
  return static_cast<int>(std::floor((world + HalfWidth) / (2.0 * HalfWidth) * Size));
}

double Luminance(vtkImageData* image, int x, int y)
{
  return (Pixel(image, x, y, 0) + Pixel(image, x, y, 1) + Pixel(image, x, y, 2)) / 3.0;
}

/// Acne: right of x = `from` shadows change no pixel by more than 2 levels.
bool NoAcne(vtkImageData* shadowed, vtkImageData* unshadowed, const std::string& name, double from)
{
  int bad = 0;
  double worst = 0.0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = std::max(ToPixel(from) + 2, 0); x < Size; ++x)
    {
      const double d = std::abs(Luminance(shadowed, x, y) - Luminance(unshadowed, x, y));
      worst = std::max(worst, d);
      bad += d > 2.0 ? 1 : 0;
    }
  }
  std::printf(
    "%s: largest change by shadows %.1f levels, %d pixels above 2\n", name.c_str(), worst, bad);
  return Check(bad == 0, name + ": shadow acne");
}

/// Peter-panning: the directional light's shadow starts at the cube's base (within 2
/// pixels) and ends where the top edge projects (within 4 pixels).
bool ShadowAttached(vtkImageData* image)
{
  const double lit = Luminance(image, ToPixel(1.5), ToPixel(1.5));
  const double end = -0.5 - 1.0 / std::tan(vtkMath::RadiansFromDegrees(Elevation));
  bool ok = true;
  for (double y = -0.4; y <= 0.4; y += 0.1)
  {
    const double base = Luminance(image, ToPixel(-0.5) - 2, ToPixel(y));
    const double inside = Luminance(image, ToPixel(end) + 4, ToPixel(y));
    const double behind = Luminance(image, ToPixel(end) - 4, ToPixel(y));
    ok = Check(base < 0.1 * lit, "the plane next to the cube's base is lit: peter-panning") && ok;
    ok = Check(inside < 0.1 * lit, "the shadow is shorter than the cube casts it") && ok;
    ok = Check(behind > 0.9 * lit, "the plane behind the shadow's end is dark") && ok;
  }
  std::printf("directional: lit %.1f, next to the base %.1f, shadow end %.1f / %.1f\n", lit,
    Luminance(image, ToPixel(-0.5) - 2, Size / 2), Luminance(image, ToPixel(end) + 4, Size / 2),
    Luminance(image, ToPixel(end) - 4, Size / 2));
  return ok;
}
}

int TestGlobalIlluminationMapperShadowBias(int, char*[])
{
  vtkSmartPointer<vtkPolyData> scene = CubeOnPlane();
  vtkSmartPointer<vtkPolyData> sphere = CoarseSphere();
  auto window = MakeWindow(Size, Size);
  const char* names[3] = { "directional", "point", "spot" };
  bool ok = true;
  for (double radius : { 0.0, 2.0 })
  {
    for (int kind = 0; kind < 3; ++kind)
    {
      const std::string name = std::string(names[kind]) + (radius > 0.0 ? " (soft)" : "");
      vtkSmartPointer<vtkLight> light = MakeLight(kind);
      vtkSmartPointer<vtkImageData> shadowed = Render(window, scene, light, true, radius);
      vtkSmartPointer<vtkImageData> unshadowed = Render(window, scene, light, false, radius);
      ok = NoAcne(shadowed, unshadowed, name + ", lit side of the cube", 0.5) && ok;
      ok = NoAcne(Render(window, sphere, light, true, radius),
             Render(window, sphere, light, false, radius), name + ", coarse sphere", -HalfWidth) &&
        ok;
      if (kind == 0)
      {
        ok = ShadowAttached(shadowed) && ok;
      }
    }
  }
  return ok ? 0 : 1;
}
