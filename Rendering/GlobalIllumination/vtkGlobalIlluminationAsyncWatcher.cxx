#include "vtkGlobalIlluminationAsyncWatcher.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindowInteractor.h"

#include <utility>

vtkStandardNewMacro(vtkGlobalIlluminationAsyncWatcher);

//------------------------------------------------------------------------------
vtkGlobalIlluminationAsyncWatcher::vtkGlobalIlluminationAsyncWatcher()
  : Command(vtkSmartPointer<vtkCallbackCommand>::New())
{
  this->Command->SetClientData(this);
  this->Command->SetCallback(&vtkGlobalIlluminationAsyncWatcher::OnTimer);
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationAsyncWatcher::~vtkGlobalIlluminationAsyncWatcher()
{
  this->Stop();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::SetFilter(vtkGlobalIlluminationFilter* filter)
{
  if (this->Filter != filter)
  {
    this->Filter = filter;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationFilter* vtkGlobalIlluminationAsyncWatcher::GetFilter()
{
  return this->Filter;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::SetPollFunction(std::function<int()> function)
{
  this->PollFunction = std::move(function);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkRenderWindowInteractor* vtkGlobalIlluminationAsyncWatcher::GetInteractor()
{
  return this->Interactor;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::Watch(vtkRenderWindowInteractor* interactor)
{
  this->Stop();
  if (!interactor)
  {
    return;
  }
  this->Interactor = interactor;
  this->ObserverTag = interactor->AddObserver(vtkCommand::TimerEvent, this->Command);
  this->TimerId = interactor->CreateRepeatingTimer(static_cast<unsigned long>(this->Interval));
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::Stop()
{
  if (vtkRenderWindowInteractor* interactor = this->Interactor)
  {
    interactor->RemoveObserver(this->ObserverTag);
    if (this->TimerId > 0)
    {
      interactor->DestroyTimer(this->TimerId);
    }
  }
  this->Interactor = nullptr;
  this->ObserverTag = 0;
  this->TimerId = -1;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationAsyncWatcher::Poll()
{
  vtkRenderWindowInteractor* interactor = this->Interactor;
  if (!interactor)
  {
    return false;
  }
  int what = WAIT;
  if (this->PollFunction)
  {
    what = this->PollFunction();
  }
  else if (this->Filter && this->Filter->PollAsynchronousResult())
  {
    what = RENDER;
  }
  if (what == STOP)
  {
    this->Stop();
  }
  if (what != RENDER)
  {
    return false;
  }
  ++this->NumberOfRenders;
  interactor->Render();
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::OnTimer(
  vtkObject*, unsigned long, void* self, void* callData)
{
  auto* watcher = static_cast<vtkGlobalIlluminationAsyncWatcher*>(self);
  // The interactors pass the id of the timer that fired: ignore the application's timers.
  if (callData && *static_cast<int*>(callData) != watcher->TimerId)
  {
    return;
  }
  watcher->Poll();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationAsyncWatcher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Filter: " << this->Filter.Get() << "\n";
  os << indent << "Interval: " << this->Interval << "\n";
  os << indent << "Interactor: " << this->Interactor.GetPointer() << "\n";
  os << indent << "Number Of Renders: " << this->NumberOfRenders << "\n";
}
