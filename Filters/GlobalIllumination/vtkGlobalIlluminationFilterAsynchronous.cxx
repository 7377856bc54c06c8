// vtkGlobalIlluminationFilter's asynchronous mode as the application sees it: whether a newer
// solution is ready (a poll re-executes the pipeline), waiting for one, and what the
// background worker is doing. RequestData hands it the scene (vtkGlobalIlluminationFilter.cxx).
#include "vtkGlobalIlluminationFilter.h"

#include "vtkGlobalIlluminationFilterInternals.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include "linkgi/AsyncSolver.h"

#include <string>

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationFilter::PollAsynchronousResult()
{
  const auto& async = this->Internals->Async;
  const auto latest = async ? async->latest() : nullptr;
  int newer = latest &&
      (latest->request != this->Internals->ShownRequest || latest->stage != this->Internals->ShownStage)
    ? 1
    : 0;
  if (this->Asynchronous && this->Internals->Partitions.Distributed())
  {
    // RequestData is collective (the surfaces' gather): all processes re-execute, or none.
    int any = newer;
    this->Controller->AllReduce(&newer, &any, 1, vtkCommunicator::MAX_OP);
    newer = any;
  }
  if (!newer)
  {
    return false;
  }
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationFilter::WaitForAsynchronousResult(double timeoutSeconds)
{
  const auto& async = this->Internals->Async;
  if (!async || this->Internals->LastRequest == 0)
  {
    return false;
  }
  async->wait(this->Internals->LastRequest, timeoutSeconds);
  return this->PollAsynchronousResult();
}

//------------------------------------------------------------------------------
vtkTypeUInt64 vtkGlobalIlluminationFilter::GetAsynchronousRequest()
{
  return this->Internals->Async ? this->Internals->LastRequest : 0;
}

bool vtkGlobalIlluminationFilter::GetAsynchronousBusy()
{
  return this->Internals->Async && this->Internals->Async->busy();
}

vtkTypeUInt64 vtkGlobalIlluminationFilter::GetAsynchronousSolving()
{
  return this->Internals->Async ? this->Internals->Async->solving() : 0;
}

double vtkGlobalIlluminationFilter::GetAsynchronousProgress()
{
  return this->Internals->Async ? this->Internals->Async->progress() : 0.0;
}

int vtkGlobalIlluminationFilter::GetAsynchronousStage()
{
  return this->Internals->Async ? static_cast<int>(this->Internals->Async->stage().stage) : 0;
}

std::string vtkGlobalIlluminationFilter::GetAsynchronousError()
{
  return this->Internals->Async ? this->Internals->Async->lastError() : std::string();
}

int vtkGlobalIlluminationFilter::GetAsynchronousStages()
{
  return this->Internals->Async ? static_cast<int>(this->Internals->Async->stage().stages) : 0;
}
