// The Cornell box with its point light (a lamp: 1/r^2), drawn by vtkGlobalIlluminationMapper
// with its default look in the three display modes side by side: direct light only
// (shadow-mapped point light), indirect light only (the filter's per-vertex
// IndirectIrradiance), combined. Compared with a baseline.
#include "RenderingTestUtilities.h"

int TestGlobalIlluminationMapperCornell(int argc, char* argv[])
{
  using namespace linkgi_test;
  vtkNew<vtkRenderer> lighting; // holds the lights the filter reads
  vtkSmartPointer<vtkPolyData> box = CornellBox(lighting);

  auto window = MakeWindow(3 * 300, 300);
  const int modes[3] = { vtkGlobalIlluminationShading::DIRECT,
    vtkGlobalIlluminationShading::INDIRECT, vtkGlobalIlluminationShading::COMBINED };
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(i / 3.0, 0.0, (i + 1) / 3.0, 1.0);
    AddLights(renderer, lighting->GetLights());
    vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, box, false);
    mapper->GetShading()->SetDisplayMode(modes[i]);
    CornellCamera(renderer);
    window->AddRenderer(renderer);
  }
  window->Render();
  return CompareWithBaseline(argc, argv, window);
}
