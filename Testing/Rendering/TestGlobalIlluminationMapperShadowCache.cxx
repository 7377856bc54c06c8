// Shadow maps are rendered again only when what they depend on changes: the lights'
// placement, the caster positions, the actor's transform, the shadow settings. Ordinary
// frames, camera moves, light colour and intensity, exposure and display mode, a modified
// input with the same points (a new irradiance array) and a headlight following the camera
// reuse them.
#include "RenderingTestUtilities.h"

#include "vtkProperty.h"

namespace
{
using namespace linkgi_test;

struct Step
{
  const char* What;
  int ExpectedRenders; // total shadow-map renders after the step
};
}

int TestGlobalIlluminationMapperShadowCache(int, char*[])
{
  vtkNew<vtkGlobalIlluminationSceneSource> source;
  source->Update();
  vtkNew<vtkPolyData> box;
  box->DeepCopy(source->GetOutput());
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkLightCollection> lights;
  source->CreateLights(lights);
  AddLights(renderer, lights);
  vtkLight* light = vtkLight::SafeDownCast(lights->GetItemAsObject(0));
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, box);
  vtkActor* actor = renderer->GetActors()->GetLastActor();
  CornellCamera(renderer);
  auto window = MakeWindow(200, 200);
  window->AddRenderer(renderer);

  bool ok = true;
  const auto expect = [&](const char* what, int renders)
  {
    window->Render();
    const int actual = mapper->GetShadowMapRenderCount();
    std::printf("%-40s shadow map renders %d (expected %d)\n", what, actual, renders);
    ok = Check(actual == renders, std::string(what) + ": wrong number of shadow map renders") && ok;
  };
  expect("first frame", 1);
  expect("second frame", 1);
  renderer->GetActiveCamera()->Azimuth(10);
  expect("camera moved", 1);
  light->SetColor(0.2, 0.4, 1.0);
  light->SetIntensity(2.0 * light->GetIntensity());
  expect("light colour and intensity changed", 1);
  mapper->GetShading()->SetExposure(3.0);
  mapper->GetShading()->SetDisplayModeToDirect();
  expect("exposure and display mode changed", 1);
  double p[3];
  light->GetPosition(p);
  light->SetPosition(p[0] + 0.05, p[1], p[2]);
  expect("light moved", 2);
  // The mapper rebuilds its vertex buffers (new point data) but uploads the same positions.
  box->Modified();
  expect("input modified, same points", 2);
  box->GetPoints()->SetPoint(
    0, box->GetPoint(0)[0], box->GetPoint(0)[1] + 0.01, box->GetPoint(0)[2]);
  box->GetPoints()->Modified();
  box->Modified();
  expect("geometry changed", 3);
  actor->SetPosition(0.01, 0, 0);
  expect("actor moved", 4);
  mapper->GetShading()->SetShadowMapResolution(256);
  expect("shadow map resolution changed", 5);
  expect("another frame", 5);
  // A headlight's shadows are never visible: it gets no map and may follow the camera.
  vtkNew<vtkLight> headlight;
  headlight->SetLightTypeToHeadlight();
  renderer->AddLight(headlight);
  expect("headlight added", 6);
  renderer->GetActiveCamera()->Azimuth(10);
  expect("camera and headlight moved", 6);
  return ok ? 0 : 1;
}
