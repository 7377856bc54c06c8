// linkgi-demo: the Cornell box lit by a point light, with multi-bounce indirect light from
// vtkGlobalIlluminationFilter, rendered offscreen to a PNG.
//
// Usage: linkgi-demo [output.png] [scene-name]
//
// vtkGlobalIlluminationMapper draws it with its default settings: per pixel, the direct
// light of the scene's lights with shadow maps, plus the filter's per-vertex indirect light;
// the scene's lamp picks the mapper's automatic look (a photographic curve exposed from the
// filter's Radiance). The README's picture is this program's output
// (Testing/Rendering/TestDemoIsReadmePicture.py keeps them the same).
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkDataArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationMapper.h"
#include "vtkGlobalIlluminationSceneSource.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{

void printTimings(vtkFieldData* fd)
{
  std::printf("solver timings (ms):");
  for (const char* name : { "LinkGI.MsBvh", "LinkGI.MsLinks", "LinkGI.MsCompress",
         "LinkGI.MsLightLinks", "LinkGI.MsBounces", "LinkGI.MsSmoothing", "LinkGI.MsTotal",
         "LinkGI.MsFilter" })
  {
    if (vtkDataArray* a = fd->GetArray(name))
    {
      std::printf(" %s=%.1f", name + 9, a->GetTuple1(0));
    }
  }
  std::printf("\n");
  for (const char* name : { "LinkGI.Elements", "LinkGI.Rays", "LinkGI.LinksRaw",
         "LinkGI.LinksCompressed", "LinkGI.LightRays" })
  {
    if (vtkDataArray* a = fd->GetArray(name))
    {
      std::printf("%s=%.0f ", name + 7, a->GetTuple1(0));
    }
  }
  std::printf("\n");
}
}

int main(int argc, char* argv[])
{
  const std::string output = argc > 1 ? argv[1] : "linkgi-demo.png";
  vtkNew<vtkGlobalIlluminationSceneSource> scene;
  scene->SetSceneName(argc > 2 ? argv[2] : "cornell");

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkLightCollection> lights;
  scene->CreateLights(lights);
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    renderer->AddLight(light);
  }

  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputConnection(scene->GetOutputPort());
  gi->SetAlbedoArrayName("Albedo");
  gi->SetEmissionArrayName("Emission");
  gi->SetLightsFromRenderer(renderer);
  gi->Update();
  vtkPolyData* lit = gi->GetOutput();
  vtkDataArray* radiance = lit->GetPointData()->GetArray("Radiance");
  if (!radiance)
  {
    std::fprintf(stderr, "linkgi-demo: the filter produced no Radiance array\n");
    return 1;
  }
  printTimings(lit->GetFieldData());

  // Shadows of the renderer's lights per pixel, indirect light from the filter's vertices.
  vtkNew<vtkGlobalIlluminationMapper> mapper;
  mapper->SetInputData(lit);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);

  renderer->ResetCamera();
  if (scene->GetSceneName() == std::string("cornell"))
  {
    // The camera of the published Cornell box data, in metres like the scene.
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.278, 0.273, -0.8);
    camera->SetFocalPoint(0.278, 0.273, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(39.3);
    renderer->ResetCameraClippingRange();
  }
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(true);
  window->SetSize(720, 720);
  window->SetMultiSamples(4);
  window->AddRenderer(renderer);
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  const std::chrono::duration<double, std::milli> first = std::chrono::steady_clock::now() - start;
  std::printf("render timings (ms): first frame (shaders and %d shadow map render) = %.1f\n",
    mapper->GetShadowMapRenderCount(), first.count());

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  std::printf("wrote %s\n", output.c_str());
  return 0;
}
