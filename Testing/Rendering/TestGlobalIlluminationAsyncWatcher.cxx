// vtkGlobalIlluminationAsyncWatcher: the interactor's timer ticks poll an asynchronous
// filter, a newer result renders the window exactly once (which re-executes the filter
// with it), the application's own timers are no polls, and Stop() (or the interactor going
// away first) leaves nothing behind.
#include "RenderingTestUtilities.h"

#include "vtkCommand.h"
#include "vtkGlobalIlluminationAsyncWatcher.h"
#include "vtkCallbackCommand.h"
#include "vtkGenericRenderWindowInteractor.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

int TestGlobalIlluminationAsyncWatcher(int, char*[])
{
  using namespace linkgi_test;
  bool ok = true;
  vtkNew<vtkPlaneSource> floor; // large enough that a result takes a while
  floor->SetResolution(40, 40);
  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputConnection(floor->GetOutputPort());
  gi->SetRaysPerVertex(64);
  gi->SetAsynchronous(true);
  const double above[3] = { 0, 0, 1 }, origin[3] = { 0, 0, 0 }, white[3] = { 1, 1, 1 };
  gi->AddLight(SceneLight(above, origin, 0.0, 1.0, white)); // directional: E = 1

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkGlobalIlluminationMapper> mapper;
  mapper->SetInputConnection(gi->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  auto window = MakeWindow(64, 64);
  window->AddRenderer(renderer);
  // The interactor of an embedding toolkit: this test is the toolkit, which creates the
  // platform timers and fires their ticks (an X interactor would need an event loop).
  auto interactor = vtkSmartPointer<vtkGenericRenderWindowInteractor>::New();
  interactor->SetRenderWindow(window);
  interactor->SetInteractorStyle(nullptr); // so the watcher's is the one TimerEvent observer
  interactor->Enable();
  vtkNew<vtkCallbackCommand> createTimer;
  createTimer->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    auto* generic = static_cast<vtkGenericRenderWindowInteractor*>(caller);
    generic->SetTimerEventPlatformId(generic->GetTimerEventId());
  });
  interactor->AddObserver(vtkCommand::CreateTimerEvent, createTimer);

  vtkNew<vtkGlobalIlluminationAsyncWatcher> watcher;
  watcher->SetFilter(gi);
  watcher->SetInterval(5);
  watcher->Watch(interactor);
  ok &= Check(watcher->GetInteractor() == interactor && watcher->GetTimerId() > 0,
    "Watch() created a timer on the interactor");
  const auto field = [&](const char* name) {
    return gi->GetOutput()->GetFieldData()->GetArray(name)->GetTuple1(0);
  };
  // Renders (a new request to the worker) and ticks until the output shows that request.
  // The watcher must render exactly once for it, unless the worker was so quick that the
  // render itself already showed it (unlikely with this mesh, but a race, not an error).
  const auto settle = [&](double request) {
    const int renders = watcher->GetNumberOfRenders();
    window->Render();
    const bool early = field("LinkGI.ShownRequest") == request;
    int tick = watcher->GetTimerId(), other = tick + 1000;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(40);
    while (field("LinkGI.ShownRequest") != request && std::chrono::steady_clock::now() < deadline)
    {
      interactor->InvokeEvent(vtkCommand::TimerEvent, &other); // the application's timer
      ok &= Check(watcher->GetNumberOfRenders() == renders, "another timer's tick polls nothing");
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
    }
    ok &= Check(field("LinkGI.ShownRequest") == request, "the result arrived within 40 s");
    ok &= Check(watcher->GetNumberOfRenders() == renders + (early ? 0 : 1),
      "the new result rendered the window once");
    for (int i = 0; i < 5; ++i)
    {
      interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
    }
    ok &= Check(watcher->GetNumberOfRenders() == renders + (early ? 0 : 1), "no new result, no render");
  };
  settle(1.0);
  const auto direct = [&] {
    return gi->GetOutput()->GetPointData()->GetArray("DirectIrradiance")->GetRange(0)[1];
  };
  ok &= Check(std::abs(direct() - 1.0) < 1e-3, "the render re-executed the filter with the result");
  gi->GetLight(0)->SetIntensity(2.0);
  settle(2.0);
  ok &= Check(std::abs(direct() - 2.0) < 2e-3, "and again after the light changed");
  ok &= Check(watcher->GetNumberOfRenders() >= 1, "the watcher rendered");

  watcher->Stop();
  ok &= Check(!interactor->HasObserver(vtkCommand::TimerEvent) && watcher->GetTimerId() == -1,
    "Stop() removed the observer and the timer");

  // A poll function instead of the filter (the ParaView plugin's): WAIT renders nothing,
  // RENDER renders once per tick, STOP ends the watch.
  std::vector<int> answers = { vtkGlobalIlluminationAsyncWatcher::WAIT,
    vtkGlobalIlluminationAsyncWatcher::RENDER, vtkGlobalIlluminationAsyncWatcher::STOP };
  std::size_t asked = 0;
  watcher->SetPollFunction([&] { return answers[std::min(asked++, answers.size() - 1)]; });
  watcher->Watch(interactor);
  const int before = watcher->GetNumberOfRenders();
  int tick = watcher->GetTimerId();
  interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
  ok &= Check(watcher->GetNumberOfRenders() == before, "WAIT: no render");
  interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
  ok &= Check(watcher->GetNumberOfRenders() == before + 1, "RENDER: one render");
  interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
  ok &= Check(watcher->GetTimerId() == -1 && watcher->GetInteractor() == nullptr &&
      !interactor->HasObserver(vtkCommand::TimerEvent),
    "STOP: the watch ended");
  ok &= Check(asked == 3 && watcher->GetNumberOfRenders() == before + 1,
    "the function was asked once per tick");
  watcher->SetPollFunction(nullptr);

  watcher->Watch(interactor);
  window->SetInteractor(nullptr);
  interactor = nullptr; // the interactor goes first: the watcher holds it weakly
  ok &= Check(watcher->GetInteractor() == nullptr && !watcher->Poll(), "a gone interactor is no crash");
  watcher->Stop();
  return ok ? 0 : 1;
}
