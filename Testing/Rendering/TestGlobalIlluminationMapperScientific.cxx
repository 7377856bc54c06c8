// A scientific dataset: an isosurface of vtkRTAnalyticSource over a plane, lit by a point
// light and a directional light; direct light only (left) and combined with the filter's
// indirect light (right). Compared with a baseline.
#include "RenderingTestUtilities.h"

int TestGlobalIlluminationMapperScientific(int argc, char* argv[])
{
  using namespace linkgi_test;
  vtkNew<vtkRenderer> lighting;
  AddIsosurfaceLights(lighting);
  vtkSmartPointer<vtkPolyData> scene = Illuminate(IsosurfaceOverPlane(), lighting, 64);
  const double exposure = 0.6 * AutoExposure(scene->GetPointData()->GetArray("Radiance"));

  auto window = MakeWindow(2 * 350, 300);
  for (int i = 0; i < 2; ++i)
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(i / 2.0, 0.0, (i + 1) / 2.0, 1.0);
    AddLights(renderer, lighting->GetLights());
    vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, scene);
    mapper->GetShading()->SetDisplayMode(
      i == 0 ? vtkGlobalIlluminationShading::DIRECT : vtkGlobalIlluminationShading::COMBINED);
    mapper->GetShading()->SetExposure(exposure);
    IsosurfaceCamera(renderer);
    window->AddRenderer(renderer);
  }
  window->Render();
  return CompareWithBaseline(argc, argv, window);
}
