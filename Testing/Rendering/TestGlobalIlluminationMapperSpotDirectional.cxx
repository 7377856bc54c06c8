// A spot light and a directional light over objects on the ground: direct light only
// (left: the spot's 2D perspective shadow map and the directional light's orthographic
// one, with PCF edges) and combined with the filter's indirect light (right).
// Compared with a baseline.
#include "RenderingTestUtilities.h"

int TestGlobalIlluminationMapperSpotDirectional(int argc, char* argv[])
{
  using namespace linkgi_test;
  vtkNew<vtkRenderer> lighting;
  const double spotPosition[3] = { -1.2, -1.1, 2.8 }, spotFocal[3] = { 0.0, 0.1, 0 };
  const double warm[3] = { 1.0, 0.85, 0.6 }, cool[3] = { 0.6, 0.75, 1.0 };
  lighting->AddLight(SceneLight(spotPosition, spotFocal, 24.0, 12.0, warm, 2.0));
  const double sunFrom[3] = { 1.6, 1.2, 1.1 }, origin[3] = { 0, 0, 0 };
  lighting->AddLight(SceneLight(sunFrom, origin, 0.0, 0.35, cool));
  vtkSmartPointer<vtkPolyData> scene = Illuminate(ObjectsOnGround(), lighting, 64);
  const double exposure = 0.7 * AutoExposure(scene->GetPointData()->GetArray("Radiance"));

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
    GroundCamera(renderer);
    window->AddRenderer(renderer);
  }
  window->Render();
  return CompareWithBaseline(argc, argv, window);
}
