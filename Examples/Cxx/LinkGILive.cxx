// linkgi-live: interactive global illumination on a deforming mesh. The torso bends and
// twists while you drag the point light (the small sphere handle); the filter runs in
// asynchronous mode, so the window keeps rendering the last solution while the next one is
// computed in the background, and a moving light only re-traces shadow rays.
//
// Usage: linkgi-live [--scene torso|tearoom|...] [--rays N] [--blend A]
//        linkgi-live --record DIR FRAMES    headless: PNG frames + DIR/strip.png
//        linkgi-live --benchmark            headless: JSON frame times and update rates
//
// vtkGlobalIlluminationMapper draws it: shadow-mapped direct light of the (moving) light per
// pixel, plus the filter's per-vertex indirect light.
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkGlobalIlluminationAsyncWatcher.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationMapper.h"
#include "vtkGlobalIlluminationSceneSource.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkHandleWidget.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPointHandleRepresentation3D.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include "LinkGILiveRecording.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
/// The live scene: source -> asynchronous GI filter -> GI mapper, one point light.
struct LiveScene
{
  vtkNew<vtkGlobalIlluminationSceneSource> source;
  vtkNew<vtkGlobalIlluminationFilter> gi;
  vtkNew<vtkGlobalIlluminationMapper> mapper;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  vtkLight* light = nullptr;
  double lightHome[3] = { 0, 0, 0 };
  int animationTimer = 0;

  LiveScene(const char* scene, int rays, double blend, double exposure)
  {
    this->source->SetSceneName(scene);
    vtkNew<vtkLightCollection> lights;
    this->source->CreateLights(lights);
    lights->InitTraversal();
    this->light = lights->GetNextItem();
    this->light->GetPosition(this->lightHome);
    this->renderer->AddLight(this->light);

    this->gi->SetInputConnection(this->source->GetOutputPort());
    this->gi->SetAlbedoArrayName("Albedo");
    this->gi->SetEmissionArrayName("Emission");
    this->gi->SetRaysPerVertex(rays);
    this->gi->SetLightsFromRenderer(this->renderer);
    this->gi->SetAsynchronous(true);
    this->gi->SetTemporalBlend(blend);

    this->mapper->SetInputConnection(this->gi->GetOutputPort());
    this->mapper->ScalarVisibilityOff();
    // Point lights near the geometry light it over a wide range (1/r^2): the exponential
    // curve compresses it (these exposures, and Documentation/live-torso-strip.png, are
    // for it); the default display is calibrated to VTK's own shading instead.
    this->mapper->GetShading()->SetToneMappingToExponential();
    this->mapper->GetShading()->SetExposure(exposure);
    vtkNew<vtkActor> actor;
    actor->SetMapper(this->mapper);
    this->renderer->AddActor(actor);
    this->renderer->SetBackground(0.1, 0.1, 0.12);
    this->window->AddRenderer(this->renderer);
    this->window->SetSize(640, 640);
    this->renderer->ResetCamera();
    this->renderer->GetActiveCamera()->Elevation(20);
    this->renderer->GetActiveCamera()->Zoom(std::string(scene) == "torso" ? 2.2 : 1.3);
  }

  /// Off: the mapper draws the source directly (no indirect light) and the filter no longer
  /// follows the light, so nothing is solved; for the frame-time benchmark.
  void EnableGlobalIllumination(bool on)
  {
    vtkAlgorithm* upstream = on ? static_cast<vtkAlgorithm*>(this->gi) : this->source.Get();
    this->mapper->SetInputConnection(upstream->GetOutputPort());
    this->gi->RemoveAllLights();
    if (on)
    {
      this->gi->SetLightsFromRenderer(this->renderer);
    }
  }
  /// Animation time t (seconds): the torso bends back and forth, the light circles.
  void SetTime(double t, bool moveLight, bool deform = true)
  {
    if (deform)
    {
      this->source->SetDeformation(0.8 * std::sin(0.9 * t));
    }
    if (moveLight)
    {
      const double r = 0.6;
      this->light->SetPosition(this->lightHome[0] + r * std::cos(t), this->lightHome[1],
        this->lightHome[2] + r * std::sin(t));
    }
  }
};

int Interactive(LiveScene& live)
{
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(live.window);
  // Drag the handle to move the point light.
  vtkNew<vtkPointHandleRepresentation3D> handle;
  handle->SetWorldPosition(live.lightHome);
  vtkNew<vtkHandleWidget> widget;
  widget->SetInteractor(interactor);
  widget->SetRepresentation(handle);
  vtkNew<vtkCallbackCommand> moveLight;
  moveLight->SetClientData(&live);
  moveLight->SetCallback([](vtkObject* caller, unsigned long, void* data, void*) {
    auto* w = static_cast<vtkHandleWidget*>(caller);
    double p[3];
    static_cast<vtkPointHandleRepresentation3D*>(w->GetRepresentation())->GetWorldPosition(p);
    static_cast<LiveScene*>(data)->light->SetPosition(p);
  });
  widget->AddObserver(vtkCommand::InteractionEvent, moveLight);
  widget->On();
  // Deform on a timer.
  vtkNew<vtkCallbackCommand> animate;
  animate->SetClientData(&live);
  animate->SetCallback([](vtkObject* caller, unsigned long, void* data, void* timerId) {
    if (timerId && *static_cast<int*>(timerId) != static_cast<LiveScene*>(data)->animationTimer)
    {
      return; // the watcher's timer
    }
    static double t = 0.0;
    t += 0.05;
    static_cast<LiveScene*>(data)->SetTime(t, false);
    static_cast<vtkRenderWindowInteractor*>(caller)->Render();
  });
  interactor->AddObserver(vtkCommand::TimerEvent, animate);
  interactor->Initialize();
  live.animationTimer = interactor->CreateRepeatingTimer(50);
  // New GI results re-render as they arrive, polled every 20 ms.
  vtkNew<vtkGlobalIlluminationAsyncWatcher> watcher;
  watcher->SetFilter(live.gi);
  watcher->SetInterval(20);
  watcher->Watch(interactor);
  live.window->Render();
  interactor->Start();
  return 0;
}
}

int main(int argc, char* argv[])
{
  std::string scene = "torso", record;
  int rays = 256, frames = 24;
  double blend = 0.5;
  bool benchmark = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--scene" && i + 1 < argc)
      scene = argv[++i];
    else if (arg == "--rays" && i + 1 < argc)
      rays = std::atoi(argv[++i]);
    else if (arg == "--blend" && i + 1 < argc)
      blend = std::atof(argv[++i]);
    else if (arg == "--record" && i + 2 < argc)
    {
      record = argv[++i];
      frames = std::atoi(argv[++i]);
    }
    else if (arg == "--benchmark")
      benchmark = true;
    else
    {
      std::fprintf(stderr, "usage: linkgi-live [--scene S] [--rays N] [--blend A] "
                           "[--record DIR FRAMES | --benchmark]\n");
      return 2;
    }
  }
  LiveScene live(scene.c_str(), rays, blend, scene == "torso" ? 1.0 : 0.5);
  if (benchmark)
  {
    // The torso deforms; every other scene stays still while its light moves.
    const bool deform = scene == "torso";
    return linkgi_live::Benchmark(live.window, live.gi,
      [&](double t, bool light) { live.SetTime(t, light, deform); },
      [&](bool on) { live.EnableGlobalIllumination(on); }, scene.c_str(), !deform);
  }
  if (!record.empty())
  {
    return linkgi_live::Record(live.window, live.gi, record, frames,
      [&](double t) { live.SetTime(t, true); });
  }
  return Interactive(live);
}
