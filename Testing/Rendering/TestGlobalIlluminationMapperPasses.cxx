// The mapper keeps VTK's shader tags, so render passes compose with it.
// - vtkSSAOPass reads the position and normal that the lighting code leaves in place: with
//   it, the Cornell box darkens along the concave edge between ceiling and back wall, while
//   the middle of the back wall keeps its brightness, and no pixel gets brighter.
// - vtkToneMappingPass: the mapper with linear output (gamma 2.2, the encoding that pass
//   expects) under the pass's exponential curve must give the image of the mapper's own
//   exponential curve.
#include "RenderingTestUtilities.h"

#include "vtkCoordinate.h"
#include "vtkRenderStepsPass.h"
#include "vtkSSAOPass.h"
#include "vtkToneMappingPass.h"

#include <array>

namespace
{
using namespace linkgi_test;

/// Where the world point (x, y, z) projects in `renderer` (which must be in its window).
std::array<int, 2> Project(vtkRenderer* renderer, double x, double y, double z)
{
  vtkNew<vtkCoordinate> coordinate;
  coordinate->SetCoordinateSystemToWorld();
  coordinate->SetValue(x, y, z);
  const int* d = coordinate->GetComputedDisplayValue(renderer);
  return { { d[0], d[1] } };
}

/// Mean luminance over the 7 x 7 pixels around d.
double MeanLuminanceAt(vtkImageData* image, const std::array<int, 2>& d)
{
  double sum = 0.0;
  for (int j = -3; j <= 3; ++j)
  {
    for (int i = -3; i <= 3; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        sum += Pixel(image, d[0] + i, d[1] + j, k);
      }
    }
  }
  return sum / (49.0 * 3.0);
}

vtkSmartPointer<vtkRenderer> Box(
  vtkPolyData* box, vtkRenderer* lighting, vtkRenderPass* pass, int toneMapping, double exposure)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  AddLights(renderer, lighting->GetLights());
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, box);
  mapper->GetShading()->SetToneMapping(toneMapping);
  mapper->GetShading()->SetExposure(exposure);
  CornellCamera(renderer);
  if (pass)
  {
    renderer->SetPass(pass);
  }
  return renderer;
}

bool CheckSSAO(vtkRenderWindow* window, vtkPolyData* box, vtkRenderer* lighting, double exposure)
{
  vtkSmartPointer<vtkRenderer> plain =
    Box(box, lighting, nullptr, vtkGlobalIlluminationShading::EXPONENTIAL, exposure);
  vtkSmartPointer<vtkImageData> before = RenderAlone(window, plain);
  const std::array<int, 2> edge = Project(plain, 0.30, 0.535, 0.559); // below the ceiling
  const std::array<int, 2> wall = Project(plain, 0.12, 0.40, 0.559);  // back wall, open
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkSSAOPass> ssao;
  ssao->SetDelegatePass(steps);
  ssao->SetRadius(0.08);
  ssao->SetBias(0.001);
  ssao->SetKernelSize(32);
  ssao->SetBlur(true);
  vtkSmartPointer<vtkRenderer> occluded =
    Box(box, lighting, ssao, vtkGlobalIlluminationShading::EXPONENTIAL, exposure);
  vtkSmartPointer<vtkImageData> after = RenderAlone(window, occluded);

  const double edgeBefore = MeanLuminanceAt(before, edge), edgeAfter = MeanLuminanceAt(after, edge);
  const double wallBefore = MeanLuminanceAt(before, wall), wallAfter = MeanLuminanceAt(after, wall);
  int brighter = 0;
  for (int p = 0; p < before->GetNumberOfPoints(); ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      brighter += after->GetPointData()->GetScalars()->GetComponent(p, k) >
          before->GetPointData()->GetScalars()->GetComponent(p, k) + 3.0
        ? 1
        : 0;
    }
  }
  std::printf("SSAO: ceiling edge %.1f -> %.1f, back wall %.1f -> %.1f, %d values brighter\n",
    edgeBefore, edgeAfter, wallBefore, wallAfter, brighter);
  bool ok = Check(edgeAfter < 0.9 * edgeBefore, "SSAO did not darken the concave edge");
  ok = Check(wallAfter > 0.95 * wallBefore, "SSAO darkened the open wall") && ok;
  return Check(brighter < before->GetNumberOfPoints() / 100, "SSAO brightened the image") && ok;
}

bool CheckToneMappingPass(
  vtkRenderWindow* window, vtkPolyData* box, vtkRenderer* lighting, double exposure)
{
  vtkSmartPointer<vtkImageData> own = RenderAlone(
    window, Box(box, lighting, nullptr, vtkGlobalIlluminationShading::EXPONENTIAL, exposure));
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkToneMappingPass> toneMapping;
  toneMapping->SetDelegatePass(steps);
  toneMapping->SetToneMappingType(vtkToneMappingPass::Exponential);
  toneMapping->SetExposure(exposure);
  vtkSmartPointer<vtkImageData> pass =
    RenderAlone(window, Box(box, lighting, toneMapping, vtkGlobalIlluminationShading::LINEAR, 1.0));
  double worst = 0.0, total = 0.0;
  const int n = own->GetNumberOfPoints();
  for (int p = 0; p < n; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double d = std::abs(own->GetPointData()->GetScalars()->GetComponent(p, k) -
        pass->GetPointData()->GetScalars()->GetComponent(p, k));
      worst = std::max(worst, d);
      total += d;
    }
  }
  std::printf(
    "vtkToneMappingPass vs the mapper's own curve: largest difference %.0f, mean %.3f levels\n",
    worst, total / (3.0 * n));
  return Check(worst <= 3.0 && total / (3.0 * n) <= 0.5,
    "vtkToneMappingPass disagrees with the mapper's curve");
}
}

int TestGlobalIlluminationMapperPasses(int, char*[])
{
  vtkNew<vtkRenderer> lighting;
  vtkSmartPointer<vtkPolyData> box = CornellBox(lighting);
  const double exposure = AutoExposure(box->GetPointData()->GetArray("Radiance"));
  auto window = MakeWindow(300, 300);
  bool ok = CheckSSAO(window, box, lighting, exposure);
  ok = CheckToneMappingPass(window, box, lighting, exposure) && ok;
  return ok ? 0 : 1;
}
