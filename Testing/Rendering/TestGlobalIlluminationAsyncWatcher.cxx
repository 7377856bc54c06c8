// vtkGlobalIlluminationAsyncWatcher: the interactor's timer ticks poll an asynchronous
// filter, a newer result renders the window exactly once (which re-executes the filter
// with it), the application's own timers are no polls, and Stop() (or the interactor going
// away first) leaves nothing behind.
#include "RenderingTestUtilities.h"

#include "vtkCommand.h"
#include "vtkGlobalIlluminationAsyncWatcher.h"
#include "vtkCallbackCommand.h"
#include "vtkGenericRenderWindowInteractor.h"

#include <chrono>
#include <thread>

int TestGlobalIlluminationAsyncWatcher(int, char*[])
{
  using namespace linkgi_test;
  bool ok = true;
  vtkNew<vtkPlaneSource> floor;
  floor->SetResolution(8, 8);
  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputConnection(floor->GetOutputPort());
  gi->SetRaysPerVertex(16);
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
  window->Render(); // hands the first request to the worker; shows zeros meanwhile
  const auto direct = [&] {
    return gi->GetOutput()->GetPointData()->GetArray("DirectIrradiance")->GetRange(0)[1];
  };
  ok &= Check(direct() == 0.0, "before the first result the output is black");

  int tick = watcher->GetTimerId(), other = tick + 1000;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(40); // within ctest's 60 s
  while (watcher->GetNumberOfRenders() == 0 && std::chrono::steady_clock::now() < deadline)
  {
    interactor->InvokeEvent(vtkCommand::TimerEvent, &other); // the application's timer
    if (watcher->GetNumberOfRenders() != 0)
    {
      ok &= Check(false, "another timer's tick polls nothing");
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
  }
  ok &= Check(watcher->GetNumberOfRenders() == 1, "the new result rendered the window once");
  if (watcher->GetNumberOfRenders() == 0)
  {
    vtkFieldData* fd = gi->GetOutput()->GetFieldData();
    std::printf("no result within 40 s: LinkGI.Pending %g, LinkGI.ShownRequest %g\n",
      fd->GetArray("LinkGI.Pending")->GetTuple1(0), fd->GetArray("LinkGI.ShownRequest")->GetTuple1(0));
    return 1;
  }
  ok &= Check(std::abs(direct() - 1.0) < 1e-3, "the render re-executed the filter with it");
  for (int i = 0; i < 5; ++i)
  {
    interactor->InvokeEvent(vtkCommand::TimerEvent, &tick);
  }
  ok &= Check(watcher->GetNumberOfRenders() == 1, "no new result, no render");

  watcher->Stop();
  ok &= Check(!interactor->HasObserver(vtkCommand::TimerEvent) && watcher->GetTimerId() == -1,
    "Stop() removed the observer and the timer");

  watcher->Watch(interactor);
  window->SetInteractor(nullptr);
  interactor = nullptr; // the interactor goes first: the watcher holds it weakly
  ok &= Check(watcher->GetInteractor() == nullptr && !watcher->Poll(), "a gone interactor is no crash");
  watcher->Stop();
  return ok ? 0 : 1;
}
