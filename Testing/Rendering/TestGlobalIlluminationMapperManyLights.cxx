// Eight shadowed lights at once: four point lights, two spots, two directional lights,
// each with its own colour, over objects on the ground (no indirect light).
// - Light is additive, so with linear output the image with all eight lights must equal
//   the sum of the eight images with one light each (within rounding). A light reading
//   another light's shadow map layers would break the sum.
// - Every light must matter: each single-light image has lit pixels, and turning shadows
//   off brightens the shadows the eight lights cast.
// - The tone-mapped image with all lights is compared with a baseline.
#include "RenderingTestUtilities.h"

namespace
{
using namespace linkgi_test;

std::vector<vtkSmartPointer<vtkLight>> EightLights()
{
  std::vector<vtkSmartPointer<vtkLight>> lights;
  const double target[3] = { 0, 0, 0.3 };
  const double colors[8][3] = { { 1, 0.3, 0.3 }, { 0.3, 1, 0.3 }, { 0.3, 0.3, 1 }, { 1, 1, 0.3 },
    { 1, 0.3, 1 }, { 0.3, 1, 1 }, { 1, 0.7, 0.4 }, { 0.5, 0.6, 1 } };
  for (int i = 0; i < 8; ++i)
  {
    const double a = 2.0 * vtkMath::Pi() * i / 8.0;
    const double position[3] = { 1.6 * std::cos(a), 1.6 * std::sin(a), i < 6 ? 1.2 : 1.0 };
    const double cone = i < 4 ? 180.0 : (i < 6 ? 35.0 : 0.0); // point, spot, directional
    const double intensity = i < 6 ? 0.6 : 0.15;
    lights.push_back(SceneLight(position, target, cone, intensity, colors[i], 1.0));
  }
  return lights;
}

vtkSmartPointer<vtkRenderer> Scene(
  vtkPolyData* data, const std::vector<vtkLight*>& lights, bool linear, bool shadows = true)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  for (vtkLight* light : lights)
  {
    renderer->AddLight(light);
  }
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, data);
  mapper->GetShading()->SetDisplayModeToDirect();
  mapper->GetShading()->SetShadows(shadows);
  mapper->GetShading()->SetShadowMapResolution(512); // 28 layers: keep the test fast
  mapper->GetShading()->SetExposure(2.0); // the eight lights give about 0.4 on the ground
  if (linear)
  {
    mapper->GetShading()->SetToneMappingToLinear();
    mapper->GetShading()->SetGamma(1.0);
    mapper->GetShading()->SetExposure(4.5); // the brightest sum stays below 255
  }
  GroundCamera(renderer);
  return renderer;
}
}

int TestGlobalIlluminationMapperManyLights(int argc, char* argv[])
{
  vtkSmartPointer<vtkPolyData> scene = ObjectsOnGround();
  std::vector<vtkSmartPointer<vtkLight>> lights = EightLights();
  std::vector<vtkLight*> all;
  for (auto& light : lights)
  {
    all.push_back(light);
  }
  auto window = MakeWindow(400, 300);
  vtkSmartPointer<vtkImageData> together = RenderAlone(window, Scene(scene, all, true));
  const int n = together->GetNumberOfPoints();
  std::vector<double> sum(3 * static_cast<std::size_t>(n), 0.0);
  bool ok = true;
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    vtkSmartPointer<vtkImageData> alone = RenderAlone(window, Scene(scene, { lights[i] }, true));
    double peak = 0.0;
    for (int p = 0; p < n; ++p)
    {
      for (int k = 0; k < 3; ++k)
      {
        const double v = alone->GetPointData()->GetScalars()->GetComponent(p, k);
        sum[3 * p + k] += v;
        peak = std::max(peak, v);
      }
    }
    ok = Check(peak > 20.0, "light " + std::to_string(i) + " lights nothing") && ok;
  }
  double worst = 0.0, total = 0.0, brightest = 0.0;
  for (int p = 0; p < n; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double v = together->GetPointData()->GetScalars()->GetComponent(p, k);
      worst = std::max(worst, std::abs(v - sum[3 * p + k]));
      total += std::abs(v - sum[3 * p + k]);
      brightest = std::max(brightest, v);
    }
  }
  std::printf("8 lights vs the sum of single lights: largest difference %.1f, mean %.3f levels "
              "(brightest pixel %.0f)\n",
    worst, total / (3.0 * n), brightest);
  ok = Check(brightest < 255.0, "the linear image clips; lower the exposure") && ok;
  ok = Check(worst <= 5.0 && total / (3.0 * n) <= 0.6, "light is not additive over 8 lights") && ok;

  vtkSmartPointer<vtkImageData> unshadowed = RenderAlone(window, Scene(scene, all, true, false));
  int brighter = 0;
  for (int p = 0; p < n; ++p)
  {
    const double gain = unshadowed->GetPointData()->GetScalars()->GetComponent(p, 0) +
      unshadowed->GetPointData()->GetScalars()->GetComponent(p, 1) +
      unshadowed->GetPointData()->GetScalars()->GetComponent(p, 2) -
      together->GetPointData()->GetScalars()->GetComponent(p, 0) -
      together->GetPointData()->GetScalars()->GetComponent(p, 1) -
      together->GetPointData()->GetScalars()->GetComponent(p, 2);
    brighter += gain > 20.0 ? 1 : 0;
  }
  std::printf("%d pixels are brighter by more than 20 levels without shadows\n", brighter);
  ok = Check(brighter > 2000, "the lights cast no shadows") && ok;

  vtkSmartPointer<vtkRenderer> shown = Scene(scene, all, false);
  RenderAlone(window, shown);
  return (CompareWithBaseline(argc, argv, window) == 0 && ok) ? 0 : 1;
}
