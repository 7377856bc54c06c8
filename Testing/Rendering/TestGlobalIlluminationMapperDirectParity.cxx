// The mapper's direct light agrees with vtkGlobalIlluminationFilter's.
//
// 1. A gently curved, finely tessellated height field with varying albedo under a point, a
//    spot and a directional light, none of which can be shadowed: the mapper's per-pixel
//    DIRECT image is compared with the filter's per-vertex DirectIrradiance * albedo / pi,
//    drawn (a) by the mapper itself as if it were indirect light (same tone mapping code)
//    and (b) as vertex colours tone mapped on the CPU (checks the shader's tone curve and
//    gamma too). Only interpolation (per pixel versus per vertex) may differ.
// 2. The Cornell box: the mapper's COMBINED image against the filter's Radiance as CPU
//    tone-mapped vertex colours. Here shadow boundaries differ (shadow maps versus
//    oversampled shadow rays), so the test bounds the median and the mean difference.
#include "RenderingTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataNormals.h"
#include "vtkPoints.h"
#include "vtkProperty.h"

#include <cmath>

namespace
{
using namespace linkgi_test;

vtkSmartPointer<vtkPolyData> HeightField()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1, -1, 0);
  plane->SetPoint1(1, -1, 0);
  plane->SetPoint2(-1, 1, 0);
  plane->SetResolution(120, 120);
  plane->Update();
  vtkNew<vtkPolyData> field;
  field->DeepCopy(plane->GetOutput());
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(field->GetNumberOfPoints());
  for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
  {
    double p[3];
    field->GetPoint(i, p);
    p[2] = 0.08 * std::sin(3.0 * p[0]) * std::cos(2.0 * p[1]);
    field->GetPoints()->SetPoint(i, p);
    albedo->SetTuple3(i, 0.45 + 0.3 * p[0], 0.6, 0.45 - 0.3 * p[1]);
  }
  field->GetPointData()->AddArray(albedo);
  field->GetPointData()->SetNormals(nullptr);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(field);
  normals->SplittingOff();
  normals->Update();
  return normals->GetOutput();
}

void AddUnshadowableLights(vtkRenderer* renderer)
{
  vtkNew<vtkLight> point;
  point->SetPositional(true);
  point->SetConeAngle(180);
  point->SetPosition(0.3, -0.2, 1.2);
  point->SetColor(1.0, 0.9, 0.8);
  vtkNew<vtkLight> spot;
  spot->SetPositional(true);
  spot->SetPosition(-1.0, 0.8, 1.5);
  spot->SetFocalPoint(0, 0, 0);
  spot->SetConeAngle(80); // covers the whole field: no cone edge to interpolate
  spot->SetExponent(3);
  spot->SetIntensity(2.0);
  vtkNew<vtkLight> sun;
  sun->SetPositional(false);
  sun->SetPosition(0.5, 0.3, 1.0);
  sun->SetFocalPoint(0, 0, 0);
  sun->SetColor(0.6, 0.7, 1.0);
  sun->SetIntensity(0.5);
  for (vtkLight* light : { point.Get(), spot.Get(), sun.Get() })
  {
    light->SetLightTypeToSceneLight();
    renderer->AddLight(light);
  }
}

/// L = albedo / pi * E per point, tone mapped like the shader (exponential, gamma 2.2).
vtkSmartPointer<vtkUnsignedCharArray> ToneMapped(
  vtkPolyData* data, const char* irradiance, double exposure, bool irradianceIsRadiance)
{
  vtkDataArray* e = data->GetPointData()->GetArray(irradiance);
  vtkDataArray* albedo = data->GetPointData()->GetArray("Albedo");
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double l = irradianceIsRadiance
        ? e->GetComponent(i, k)
        : albedo->GetComponent(i, k) / vtkMath::Pi() * e->GetComponent(i, k);
      const double display = std::pow(1.0 - std::exp(-exposure * l), 1.0 / 2.2);
      colors->SetComponent(i, k, std::min(255.0, std::max(0.0, display * 255.0 + 0.5)));
    }
  }
  return colors;
}

/// Renders `actor` in a renderer set up by `setup` (lights, camera) and captures it.
template <typename Setup>
vtkSmartPointer<vtkImageData> Snapshot(vtkRenderWindow* window, vtkActor* actor, Setup setup)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 0, 1); // magenta marks the background
  renderer->AddActor(actor);
  setup(renderer);
  return RenderAlone(window, renderer);
}

vtkSmartPointer<vtkActor> VertexColorActor(vtkPolyData* data, vtkUnsignedCharArray* colors)
{
  vtkNew<vtkPolyData> shown;
  shown->ShallowCopy(data);
  shown->GetPointData()->SetScalars(colors);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(shown);
  mapper->SetColorModeToDirectScalars();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  return actor;
}

vtkSmartPointer<vtkActor> MapperActor(
  vtkPolyData* data, int mode, const char* indirect, double exposure)
{
  vtkNew<vtkGlobalIlluminationMapper> mapper;
  mapper->SetInputData(data);
  mapper->GetShading()->SetDisplayMode(mode);
  mapper->GetShading()->SetIndirectIrradianceArrayName(indirect);
  mapper->GetShading()->SetExposure(exposure);
  // The photographic curve displays the radiance itself, which the filter's Radiance is
  // compared with; the default (hue preserving) display is checked against VTK's own
  // shading by python.GlobalIlluminationColourCalibration.
  mapper->GetShading()->SetToneMappingToExponential();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// Differences (in levels, max over channels) over pixels both images cover.
std::vector<double> Differences(vtkImageData* a, vtkImageData* b)
{
  std::vector<double> d;
  for (int y = 0; y < 400; ++y)
  {
    for (int x = 0; x < 400; ++x)
    {
      const auto background = [x, y](vtkImageData* i)
      { return Pixel(i, x, y, 0) == 255 && Pixel(i, x, y, 1) == 0 && Pixel(i, x, y, 2) == 255; };
      if (background(a) || background(b))
      {
        continue;
      }
      double m = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        m = std::max(m, std::abs(Pixel(a, x, y, k) - Pixel(b, x, y, k)));
      }
      d.push_back(m);
    }
  }
  std::sort(d.begin(), d.end());
  return d;
}

bool Agree(
  vtkImageData* a, vtkImageData* b, const std::string& what, double median, double mean, double p99)
{
  std::vector<double> d = Differences(a, b);
  if (!Check(d.size() > 50000, what + ": too few pixels cover the surface"))
  {
    return false;
  }
  double sum = 0.0;
  for (double v : d)
  {
    sum += v;
  }
  const double m50 = d[d.size() / 2], m99 = d[d.size() * 99 / 100], avg = sum / d.size();
  std::printf("%s: %zu pixels, difference median %.1f, mean %.2f, 99th percentile %.1f levels\n",
    what.c_str(), d.size(), m50, avg, m99);
  return Check(m50 <= median && avg <= mean && m99 <= p99, what + ": images differ");
}
}

int TestGlobalIlluminationMapperDirectParity(int, char*[])
{
  auto window = MakeWindow(400, 400);
  vtkNew<vtkRenderer> lighting;
  AddUnshadowableLights(lighting);
  vtkSmartPointer<vtkPolyData> field = Illuminate(HeightField(), lighting, 16);
  const double exposure = 2.0;
  const auto fieldView = [&](vtkRenderer* renderer)
  {
    AddLights(renderer, lighting->GetLights());
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.4, -2.2, 2.0);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 0, 1);
    renderer->ResetCameraClippingRange();
  };
  auto direct = Snapshot(
    window, MapperActor(field, vtkGlobalIlluminationShading::DIRECT, "", exposure), fieldView);
  auto perVertex = Snapshot(window,
    MapperActor(field, vtkGlobalIlluminationShading::INDIRECT, "DirectIrradiance", exposure),
    fieldView);
  auto cpu = Snapshot(window,
    VertexColorActor(field, ToneMapped(field, "DirectIrradiance", exposure, false)), fieldView);
  bool ok =
    Agree(direct, perVertex, "height field, per pixel vs per vertex (shader)", 1.0, 0.5, 2.0);
  ok =
    Agree(direct, cpu, "height field, per pixel vs per vertex (CPU tone mapping)", 1.0, 0.5, 2.0) &&
    ok;

  vtkNew<vtkRenderer> cornellLights;
  vtkSmartPointer<vtkPolyData> box = CornellBox(cornellLights);
  const double boxExposure = AutoExposure(box->GetPointData()->GetArray("Radiance"));
  const auto boxView = [&](vtkRenderer* renderer)
  {
    AddLights(renderer, cornellLights->GetLights());
    CornellCamera(renderer);
  };
  auto combined = Snapshot(window,
    MapperActor(box, vtkGlobalIlluminationShading::COMBINED, "IndirectIrradiance", boxExposure),
    boxView);
  auto radiance = Snapshot(
    window, VertexColorActor(box, ToneMapped(box, "Radiance", boxExposure, true)), boxView);
  ok =
    Agree(combined, radiance, "Cornell box, combined vs the filter's Radiance", 1.0, 2.0, 30.0) &&
    ok;
  return ok ? 0 : 1;
}
