// The default look (vtkGlobalIlluminationShading's AUTOMATIC tone mapping), for both kinds of
// scene, with no setting touched:
// - Lit on VTK's scale (a directional light with VTK's light kit; a point light with VTK's
//   default attenuation, which does not fall off): exactly the calibrated HUE_PRESERVING
//   look at Exposure 1, pixel for pixel.
// - A lamp near surfaces (the Cornell box, 1/r^2): nothing blown out (under 1 % of the box's
//   pixels white), and the coloured walls keep their hue (within 10 degrees of their
//   albedo's under the lamp's colour). The calibrated look, exposed for the same scene, fails both checks: that is
//   what the lamp look is for, and it shows the checks can fail.
// Left the Cornell box, right the objects on the ground under the light kit, compared with a
// baseline.
#include "RenderingTestUtilities.h"

#include "vtkGlobalIlluminationColors.h"
#include "vtkLightKit.h"

namespace
{
using namespace linkgi_test;

/// Hue in degrees (HSV) of the mean colour of the pixels in [x0, x1) x [y0, y1).
double MeanHue(vtkImageData* image, int x0, int x1, int y0, int y1)
{
  double c[3] = { 0, 0, 0 };
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[k] += Pixel(image, x, y, k);
      }
    }
  }
  const double top = std::max({ c[0], c[1], c[2] }), bottom = std::min({ c[0], c[1], c[2] });
  if (top <= bottom)
  {
    return 0.0;
  }
  const double d = top - bottom;
  double h = top == c[0] ? (c[1] - c[2]) / d : (top == c[1] ? 2.0 + (c[2] - c[0]) / d : 4.0 + (c[0] - c[1]) / d);
  h *= 60.0;
  return h < 0.0 ? h + 360.0 : h;
}

/// Hue of a linear albedo lit by a light of colour `light`, as displayed (sRGB).
double LitHue(double r, double g, double b, const double light[3])
{
  vtkNew<vtkImageData> one;
  one->SetDimensions(1, 1, 1);
  one->AllocateScalars(VTK_DOUBLE, 3);
  const double linear[3] = { r * light[0], g * light[1], b * light[2] };
  const double top = std::max({ linear[0], linear[1], linear[2] });
  for (int k = 0; k < 3; ++k)
  {
    one->SetScalarComponentFromDouble(
      0, 0, 0, k, vtkGlobalIlluminationColors::ToDisplay(linear[k] / top));
  }
  return MeanHue(one, 0, 1, 0, 1);
}

double HueDistance(double a, double b)
{
  const double d = std::fabs(a - b);
  return std::min(d, 360.0 - d);
}

/// The Cornell box panel (300 x 300): its walls' hues and the share of white pixels.
struct Checks
{
  double White = 0.0;
  double RedHueError = 0.0;
  double GreenHueError = 0.0;
};

Checks CheckCornell(vtkImageData* image, const double light[3])
{
  Checks checks;
  int white = 0;
  for (int y = 10; y < 290; ++y)
  {
    for (int x = 10; x < 290; ++x)
    {
      white += Pixel(image, x, y, 0) >= 250 && Pixel(image, x, y, 1) >= 250 && Pixel(image, x, y, 2) >= 250;
    }
  }
  checks.White = white / (280.0 * 280.0);
  // The scene source's wall albedos (kernels/src/Scenes.cpp) under the lamp's colour,
  // sampled mid-height.
  checks.RedHueError =
    HueDistance(MeanHue(image, 15, 45, 110, 190), LitHue(0.63, 0.065, 0.05, light));
  checks.GreenHueError =
    HueDistance(MeanHue(image, 255, 285, 110, 190), LitHue(0.14, 0.45, 0.091, light));
  return checks;
}

vtkSmartPointer<vtkRenderer> CornellView(vtkRenderer* lighting, vtkPolyData* box, bool calibrated)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  AddLights(renderer, lighting->GetLights());
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, box, calibrated);
  if (calibrated) // the look lamps had by default: calibrated, exposed for the scene
  {
    mapper->GetShading()->SetExposure(AutoExposure(box->GetPointData()->GetArray("Radiance")));
  }
  CornellCamera(renderer);
  return renderer;
}

/// ObjectsOnGround under `light` plus, with `kit`, VTK's light kit; default or calibrated look.
vtkSmartPointer<vtkRenderer> GroundView(vtkPolyData* lit, vtkLight* light, bool kit, bool calibrated)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  if (kit)
  {
    vtkNew<vtkLightKit> lightKit;
    lightKit->AddLightsToRenderer(renderer);
  }
  renderer->AddLight(light);
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, lit, calibrated);
  if (calibrated)
  {
    mapper->GetShading()->SetExposure(1.0);
  }
  GroundCamera(renderer);
  return renderer;
}

double LargestDifference(vtkImageData* a, vtkImageData* b)
{
  double largest = 0.0;
  const int* d = a->GetDimensions();
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        largest = std::max(largest, std::fabs(Pixel(a, x, y, k) - Pixel(b, x, y, k)));
      }
    }
  }
  return largest;
}
}

int TestGlobalIlluminationMapperLook(int argc, char* argv[])
{
  bool ok = true;
  auto window = MakeWindow(300, 300);

  // Scenes on VTK's scale: the default look is the calibrated one, exactly.
  const double above[3] = { 1.0, -1.5, 2.5 }, origin[3] = { 0, 0, 0 }, white[3] = { 1, 1, 1 };
  vtkSmartPointer<vtkLight> sun = SceneLight(above, origin, 0.0, 0.25, white);
  vtkSmartPointer<vtkLight> bulb = SceneLight(above, origin, 180.0, 0.8, white);
  bulb->SetAttenuationValues(1, 0, 0); // VTK's default: no falloff
  vtkSmartPointer<vtkPolyData> ground = ObjectsOnGround();
  for (vtkLight* light : { sun.Get(), bulb.Get() })
  {
    const bool kit = light == sun.Get();
    vtkNew<vtkRenderer> lighting;
    lighting->AddLight(light);
    vtkSmartPointer<vtkPolyData> lit = Illuminate(ground, lighting, 16);
    const double difference = LargestDifference(
      RenderAlone(window, GroundView(lit, light, kit, false)),
      RenderAlone(window, GroundView(lit, light, kit, true)));
    std::printf("%s: default vs calibrated look, largest difference %.0f levels\n",
      kit ? "directional light and light kit" : "point light without falloff", difference);
    ok = Check(difference == 0.0, "a scene on VTK's scale has the calibrated look by default") && ok;
  }

  // A lamp: nothing blown out, hues kept; the calibrated look fails both.
  vtkNew<vtkRenderer> lighting;
  vtkSmartPointer<vtkPolyData> box = CornellBox(lighting);
  double colour[3];
  vtkLight::SafeDownCast(lighting->GetLights()->GetItemAsObject(0))->GetDiffuseColor(colour);
  const Checks lamp = CheckCornell(RenderAlone(window, CornellView(lighting, box, false)), colour);
  const Checks calibrated =
    CheckCornell(RenderAlone(window, CornellView(lighting, box, true)), colour);
  for (const auto& c : { std::make_pair("default", lamp), std::make_pair("calibrated", calibrated) })
  {
    std::printf("Cornell box, %s look: %.2f %% white, red wall hue off by %.1f, green by %.1f degrees\n",
      c.first, 100.0 * c.second.White, c.second.RedHueError, c.second.GreenHueError);
  }
  ok = Check(lamp.White < 0.01, "the lamp-lit box is not blown out") && ok;
  ok = Check(lamp.RedHueError < 10.0 && lamp.GreenHueError < 10.0, "the walls keep their hue") && ok;
  ok = Check(calibrated.White > 0.05 && calibrated.GreenHueError > 10.0,
         "the calibrated look blows the lamp-lit box out (the checks can fail)") && ok;

  // The baseline: the default look of both scenes side by side.
  vtkNew<vtkRenderer> lightingForGround;
  lightingForGround->AddLight(sun);
  vtkSmartPointer<vtkRenderer> left = CornellView(lighting, box, false);
  vtkSmartPointer<vtkRenderer> right =
    GroundView(Illuminate(ground, lightingForGround, 16), sun, true, false);
  left->SetViewport(0.0, 0.0, 0.5, 1.0);
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  vtkRendererCollection* renderers = window->GetRenderers();
  while (renderers->GetNumberOfItems() > 0)
  {
    window->RemoveRenderer(renderers->GetFirstRenderer());
  }
  window->SetSize(600, 300);
  window->AddRenderer(left);
  window->AddRenderer(right);
  window->Render();
  return CompareWithBaseline(argc, argv, window) == 0 && ok ? 0 : 1;
}
