// linkgi-mapper-bench: frame time of vtkGlobalIlluminationMapper against a plain
// vtkOpenGLPolyDataMapper on the same scene, lights, camera path and window, once the
// shadow maps exist. Prints one JSON record per scene: milliseconds per frame of the plain
// mapper, of the global illumination mapper with its default soft (four-tap) shadow filter
// (mapper_ms, ratio) and with a single bilinear lookup per light, ShadowFilterRadius 0
// (mapper_single_ms, single_ratio).
//
// Usage: linkgi-mapper-bench [--frames N] [--size W H] [--images DIR]
//
// Scenes: the Cornell box with its point light, the Cornell box with eight lights (point,
// spot and directional), and an isosurface of vtkRTAnalyticSource over a plane with two
// lights. Each frame turns the camera by 2 degrees (camera moves reuse the shadow maps).
// The two mappers draw in alternating blocks of frames so that drift hits both alike;
// every frame ends with glFinish (WaitForCompletion).
//
// --images DIR also writes the README images: each scene drawn with direct light only and
// combined with the indirect light, side by side (DIR/<scene>-direct-vs-combined.png).
#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationMapper.h"
#include "vtkGlobalIlluminationSceneSource.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace
{
struct Scene
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Lit; // the filter's output
  vtkNew<vtkLightCollection> Lights;
  std::function<void(vtkCamera*)> Camera;
  /// The display: calibrated to VTK's shading, or a photographic curve for lamp-lit rooms.
  int ToneMapping = vtkGlobalIlluminationShading::HUE_PRESERVING;
};

vtkSmartPointer<vtkLight> MakeLight(double x, double y, double z, double fx, double fy, double fz,
  double cone, double intensity, double r, double g, double b)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(cone > 0.0);     // cone 0: directional
  light->SetAttenuationValues(0, 0, 1); // a lamp: 1/r^2
  light->SetPosition(x, y, z);
  light->SetFocalPoint(fx, fy, fz);
  light->SetConeAngle(cone > 0.0 ? cone : 30.0);
  light->SetIntensity(intensity);
  light->SetColor(r, g, b);
  return light;
}

void Illuminate(Scene& scene, vtkPolyData* input, int rays)
{
  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputData(input);
  gi->SetAlbedoArrayName("Albedo");
  gi->SetRaysPerVertex(rays);
  vtkCollectionSimpleIterator it;
  scene.Lights->InitTraversal(it);
  while (vtkLight* light = scene.Lights->GetNextLight(it))
  {
    gi->AddLight(light);
  }
  gi->Update();
  scene.Lit = gi->GetOutput();
}

void Cornell(Scene& scene, bool eightLights, int rays)
{
  vtkNew<vtkGlobalIlluminationSceneSource> source;
  source->Update();
  source->CreateLights(scene.Lights);
  if (eightLights)
  {
    scene.Name = "cornell-8-lights";
    scene.Lights->AddItem(MakeLight(0.1, 0.45, 0.1, 0.1, 0, 0.1, 180, 0.05, 1, 0.6, 0.4));
    scene.Lights->AddItem(MakeLight(0.45, 0.45, 0.1, 0.45, 0, 0.1, 180, 0.05, 0.4, 0.6, 1));
    scene.Lights->AddItem(MakeLight(0.1, 0.3, 0.5, 0.2, 0, 0.2, 180, 0.04, 0.5, 1, 0.5));
    scene.Lights->AddItem(MakeLight(0.45, 0.3, 0.5, 0.4, 0, 0.3, 180, 0.04, 1, 1, 0.6));
    scene.Lights->AddItem(MakeLight(0.05, 0.5, 0.05, 0.4, 0, 0.4, 30, 0.3, 1, 0.9, 0.8));
    scene.Lights->AddItem(MakeLight(0.5, 0.5, 0.05, 0.2, 0, 0.2, 30, 0.3, 0.8, 0.9, 1));
    scene.Lights->AddItem(MakeLight(0.3, 0.6, -0.8, 0.28, 0.2, 0.3, 0, 0.3, 1, 1, 1));
  }
  else
  {
    scene.Name = "cornell";
  }
  Illuminate(scene, source->GetOutput(), rays);
  // Lamps close to the walls light the box over a wide range (1/r^2): compress it.
  scene.ToneMapping = vtkGlobalIlluminationShading::EXPONENTIAL;
  scene.Camera = [](vtkCamera* camera)
  {
    camera->SetPosition(0.278, 0.273, -0.8); // the published camera, in metres
    camera->SetFocalPoint(0.278, 0.273, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(39.3);
  };
}

vtkSmartPointer<vtkPolyData> WithAlbedo(
  vtkPolyData* data, std::function<void(const double*, double*)> color)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(data);
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(copy->GetNumberOfPoints());
  for (vtkIdType i = 0; i < copy->GetNumberOfPoints(); ++i)
  {
    double c[3];
    color(copy->GetPoint(i), c);
    albedo->SetTuple(i, c);
  }
  copy->GetPointData()->AddArray(albedo);
  copy->GetPointData()->SetTCoords(nullptr);
  return copy;
}

void Isosurface(Scene& scene, int rays)
{
  scene.Name = "isosurface";
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-10, 10, -10, 10, -10, 10);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputConnection(wavelet->GetOutputPort());
  contour->SetValue(0, 215.0);
  contour->ComputeScalarsOff();
  contour->Update();
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-20, -20, -11);
  plane->SetPoint1(20, -20, -11);
  plane->SetPoint2(-20, 20, -11);
  plane->SetResolution(80, 80);
  plane->Update();
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(WithAlbedo(contour->GetOutput(),
    [](const double* p, double* c)
    {
      const double t =
        std::min(1.0, std::max(0.0, (p[2] + 8.0) / 16.0)); // blue to orange by height
      c[0] = 0.02 + 0.83 * t;
      c[1] = 0.08 + 0.22 * t;
      c[2] = 0.6 - 0.58 * t;
    }));
  append->AddInputData(
    WithAlbedo(plane->GetOutput(), [](const double*, double* c) { c[0] = c[1] = c[2] = 0.7; }));
  append->Update();
  scene.Lights->AddItem(MakeLight(-14, -10, 22, 0, 0, 0, 180, 700, 1, 0.9, 0.75));
  scene.Lights->AddItem(MakeLight(1, -0.4, 0.8, 0, 0, 0, 0, 0.4, 0.65, 0.75, 1));
  Illuminate(scene, append->GetOutput(), rays);
  scene.Camera = [](vtkCamera* camera)
  {
    camera->SetPosition(30, -48, 28);
    camera->SetFocalPoint(0, 0, -4);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(30);
  };
}

/// Sets the scene's tone mapping and the exposure it suggests for the scene's Radiance.
void SetDisplay(vtkGlobalIlluminationShading* shading, const Scene& scene)
{
  shading->SetToneMapping(scene.ToneMapping);
  shading->SetExposure(shading->SuggestExposure(scene.Lit->GetPointData()->GetArray("Radiance")));
}

/// A renderer drawing the scene with `mapper` under the scene's lights.
vtkSmartPointer<vtkRenderer> MakeRenderer(Scene& scene, vtkMapper* mapper)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkCollectionSimpleIterator it;
  scene.Lights->InitTraversal(it);
  while (vtkLight* light = scene.Lights->GetNextLight(it))
  {
    renderer->AddLight(light);
  }
  mapper->SetInputDataObject(scene.Lit);
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  scene.Camera(renderer->GetActiveCamera());
  renderer->ResetCameraClippingRange();
  return renderer;
}

/// Milliseconds per frame over `frames` frames, turning the camera 2 degrees per frame.
double TimeFrames(vtkRenderWindow* window, vtkRenderer* renderer, int frames)
{
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i)
  {
    renderer->GetActiveCamera()->Azimuth(2.0);
    renderer->ResetCameraClippingRange();
    window->Render();
    window->WaitForCompletion();
  }
  const std::chrono::duration<double, std::milli> elapsed =
    std::chrono::steady_clock::now() - start;
  return elapsed.count() / frames;
}

void Show(vtkRenderWindow* window, vtkRenderer* renderer)
{
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(renderer);
}

void Benchmark(Scene& scene, vtkRenderWindow* window, int frames, int width, int height)
{
  window->SetSize(width, height);
  vtkNew<vtkOpenGLPolyDataMapper> plainMapper;
  vtkNew<vtkGlobalIlluminationMapper> giMapper, singleMapper;
  SetDisplay(giMapper->GetShading(), scene);
  SetDisplay(singleMapper->GetShading(), scene);
  singleMapper->GetShading()->SetShadowFilterRadius(0.0); // one filter tap per light
  vtkSmartPointer<vtkRenderer> renderers[3] = { MakeRenderer(scene, plainMapper),
    MakeRenderer(scene, giMapper), MakeRenderer(scene, singleMapper) };

  Show(window, renderers[1]);
  const double firstFrame = TimeFrames(window, renderers[1], 1); // shaders and shadow maps
  for (vtkRenderer* renderer : renderers)
  {
    Show(window, renderer);
    TimeFrames(window, renderer, 3);
  }
  double ms[3] = { 0.0, 0.0, 0.0 };
  const int blocks = 4;
  for (int b = 0; b < blocks; ++b)
  {
    for (int k = 0; k < 3; ++k)
    {
      Show(window, renderers[k]);
      ms[k] += TimeFrames(window, renderers[k], frames / blocks) / blocks;
    }
  }
  std::printf(
    "{\"scene\": \"%s\", \"points\": %lld, \"triangles\": %lld, \"lights\": %d, "
    "\"width\": %d, \"height\": %d, \"frames\": %d, \"plain_ms\": %.2f, "
    "\"mapper_ms\": %.2f, \"ratio\": %.2f, \"mapper_single_ms\": %.2f, "
    "\"single_ratio\": %.2f, \"mapper_first_frame_ms\": %.1f, \"shadow_map_renders\": %d}\n",
    scene.Name.c_str(), static_cast<long long>(scene.Lit->GetNumberOfPoints()),
    static_cast<long long>(scene.Lit->GetNumberOfPolys()), scene.Lights->GetNumberOfItems(), width,
    height, (frames / blocks) * blocks, ms[0], ms[1], ms[1] / ms[0], ms[2], ms[2] / ms[0],
    firstFrame, giMapper->GetShadowMapRenderCount());
  std::fflush(stdout);
}

/// Direct light only and combined, side by side, for the README.
void WriteImage(Scene& scene, vtkRenderWindow* window, const std::string& directory)
{
  window->GetRenderers()->RemoveAllItems();
  window->SetSize(2 * 480, 400);
  for (int i = 0; i < 2; ++i)
  {
    vtkNew<vtkGlobalIlluminationMapper> mapper;
    mapper->GetShading()->SetDisplayMode(
      i == 0 ? vtkGlobalIlluminationShading::DIRECT : vtkGlobalIlluminationShading::COMBINED);
    SetDisplay(mapper->GetShading(), scene);
    vtkSmartPointer<vtkRenderer> renderer = MakeRenderer(scene, mapper);
    renderer->SetViewport(0.5 * i, 0.0, 0.5 * (i + 1), 1.0);
    window->AddRenderer(renderer);
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  const std::string file = directory + "/" + scene.Name + "-direct-vs-combined.png";
  writer->SetFileName(file.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  std::printf("wrote %s\n", file.c_str());
}
}

int main(int argc, char* argv[])
{
  int frames = 80, width = 800, height = 600;
  std::string images;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
    {
      frames = std::max(4, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--size") && i + 2 < argc)
    {
      width = std::atoi(argv[++i]);
      height = std::atoi(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--images") && i + 1 < argc)
    {
      images = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: %s [--frames N] [--size W H] [--images DIR]\n", argv[0]);
      return 1;
    }
  }
  const int rays = images.empty() ? 64 : 256; // the frame time does not depend on them
  // One window for everything: every window is another X connection.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(images.empty() ? 0 : 8);
  std::vector<Scene> scenes(3);
  Cornell(scenes[0], false, rays);
  Cornell(scenes[1], true, rays);
  Isosurface(scenes[2], rays);
  for (Scene& scene : scenes)
  {
    if (!images.empty())
    {
      if (scene.Name != "cornell-8-lights")
      {
        WriteImage(scene, window, images);
      }
      continue;
    }
    Benchmark(scene, window, frames, width, height);
  }
  return 0;
}
