#include "vtkGlobalIlluminationRepresentation.h"
#include "vtkGlobalIlluminationRepresentationInternals.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositeRepresentation.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationAsyncWatcher.h"
#include "vtkGlobalIlluminationCompositeMapper.h"
#include "vtkGlobalIlluminationDrawnAlbedo.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationGlobalCasters.h"
#include "vtkGlobalIlluminationLights.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVLight.h"
#include "vtkPVGlobalIlluminationStateInformation.h"
#include "vtkPVRenderView.h"
#include "vtkPVSession.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyIterator.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSession.h"
#include "vtkSMSessionClient.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSmartPointer.h"
#include "vtkVariant.h"
#include "vtkWeakPointer.h"

#include <set>
#include <string>
#include <vector>

using namespace vtkGlobalIlluminationRepresentationHelpers;

namespace
{
/// `point` (x, y, z) moved by the homogeneous `matrix`.
void Transform(vtkMatrix4x4* matrix, double point[3])
{
  double in[4] = { point[0], point[1], point[2], 1.0 }, out[4];
  matrix->MultiplyPoint(in, out);
  for (int i = 0; i < 3; ++i)
  {
    point[i] = out[3] != 0.0 ? out[i] / out[3] : out[i];
  }
}

/// The registered representation proxy whose active representation in this process is
/// `object` (its Global Illumination subproxy's), or nullptr.
vtkSMProxy* FindProxy(vtkObject* object)
{
  vtkSMProxyManager* manager = vtkSMProxyManager::IsInitialized() ? vtkSMProxyManager::GetProxyManager() : nullptr;
  vtkSMSessionProxyManager* session = manager ? manager->GetActiveSessionProxyManager() : nullptr;
  if (!session)
  {
    return nullptr;
  }
  vtkNew<vtkSMProxyIterator> it;
  it->SetSessionProxyManager(session);
  it->SetModeToOneGroup();
  for (it->Begin("representations"); !it->IsAtEnd(); it->Next())
  {
    vtkSMProxy* proxy = it->GetProxy();
    auto* composite = vtkCompositeRepresentation::SafeDownCast(proxy->GetClientSideObject());
    if (composite && composite->GetActiveRepresentation() == object)
    {
      return proxy;
    }
  }
  return nullptr;
}

/// What the progress bar says while the worker solves: which stage of a progressive update.
std::string BackgroundText(vtkGlobalIlluminationFilter* filter)
{
  const int stage = filter->GetAsynchronousStage(), stages = filter->GetAsynchronousStages();
  if (stages > 1 && stage < stages)
  {
    return "Global illumination (background, coarse " + std::to_string(stage) + " of " +
      std::to_string(stages - 1) + ")";
  }
  return stages > 1 ? "Global illumination (background, final)" : "Global illumination (background)";
}

/// Whether `filter`'s output shows the final solution of its newest request.
bool ShowsFinal(vtkGlobalIlluminationFilter* filter)
{
  vtkDataObject* output = filter->GetOutputDataObject(0);
  return static_cast<vtkTypeUInt64>(FieldInt(output, "LinkGI.ShownRequest")) >= filter->GetAsynchronousRequest() &&
    FieldInt(output, "LinkGI.ShownStage") == FieldInt(output, "LinkGI.Stages");
}

/// `a` and `b`, each true if it is true on any process of the global controller.
void AnyOverProcesses(bool& a, bool& b)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() <= 1)
  {
    return;
  }
  int local[2] = { a ? 1 : 0, b ? 1 : 0 }, global[2] = { 0, 0 };
  controller->AllReduce(local, global, 2, vtkCommunicator::MAX_OP);
  a = global[0] != 0;
  b = global[1] != 0;
}
}

vtkStandardNewMacro(vtkGlobalIlluminationRepresentation);

//------------------------------------------------------------------------------
vtkGlobalIlluminationRepresentation::vtkGlobalIlluminationRepresentation()
  : Internals(new vtkInternals)
{
  // Replace the superclass's mapper, keeping what it set up for selection.
  this->Mapper->Delete();
  vtkGlobalIlluminationCompositeMapper* mapper = vtkGlobalIlluminationCompositeMapper::New();
  mapper->SetProcessIdArrayName("vtkProcessId");
  mapper->SetCompositeIdArrayName("vtkCompositeIndex");
  this->Mapper = mapper;
  this->SetArrayIdNames(nullptr, nullptr);
  this->SuppressLOD = true;
  this->SetupDefaults();
  mapper->GetShading()->SetGlobalCasters(this->Internals->GlobalCasters);

  vtkGlobalIlluminationFilter* filter = this->Internals->Filter;
  // A render never waits for the solver unless WaitForSolution says so. Partitioned among
  // processes the filter is collective and solves synchronously (it would say so at
  // every update): there every render waits.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  filter->SetAsynchronous(!controller || controller->GetNumberOfProcesses() <= 1);
  filter->SetProgressive(true); // a coarse indirect light first, the final one after
  filter->AddObserver(vtkCommand::WarningEvent, this, &vtkGlobalIlluminationRepresentation::OnFilterEvent);
  this->Internals->Watcher->SetInterval(100);
  this->Internals->Watcher->SetPollFunction([this] { return this->PollForSolution(); });
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::OnFilterEvent(vtkObject*, unsigned long event, void* data)
{
  vtkInternals& internals = *this->Internals;
  if (event == vtkCommand::WarningEvent && data)
  {
    // The filter runs on every light change: show each of its warnings once, not per frame.
    const std::string message = static_cast<const char*>(data);
    if (internals.Warnings.insert(message).second)
    {
      vtkWarningMacro(<< message);
    }
  }
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationRepresentation::~vtkGlobalIlluminationRepresentation()
{
  this->Internals->Watcher->Stop();
  this->Internals->Watcher->SetPollFunction(nullptr);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::SetSuppressLOD(bool)
{
  this->SuppressLOD = true;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  auto cmapper = vtkCompositePolyDataMapper2::SafeDownCast(this->Mapper);
  vtkCompositeDataDisplayAttributes* attributes =
    cmapper ? cmapper->GetCompositeDataDisplayAttributes() : nullptr;
  const vtkMTimeType attributesTime = attributes ? attributes->GetMTime() : 0;

  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  vtkPVRenderView* view = vtkPVRenderView::SafeDownCast(this->GetView());
  if (request_type != vtkPVView::REQUEST_RENDER() || !view)
  {
    return 1;
  }

  // The superclass gave the mapper the delivered data; draw the lit copy instead, with the
  // block attributes (colours, visibilities) moved onto the copy's blocks.
  vtkInternals& internals = *this->Internals;
  vtkDataObject* lit =
    this->UpdateGlobalIllumination(vtkPVView::GetDeliveredPiece(inInfo, this), view->GetRenderer());
  this->Mapper->SetInputDataObject(lit);
  // A new solution may have new blocks (the attributes are kept per block object).
  const bool changed = lit != internals.Drawn || (lit && lit->GetMTime() != internals.DrawnTime);
  if (attributes && lit && (changed || attributes->GetMTime() != attributesTime))
  {
    this->PopulateBlockAttributes(attributes, lit);
  }
  internals.Drawn = lit;
  internals.DrawnTime = lit ? lit->GetMTime() : 0;

  if (!this->GetWaits())
  {
    this->WatchForSolutions(view);
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationRepresentation::GetWaits()
{
  switch (this->WaitForSolution)
  {
    case WAIT_NEVER:
      return false;
    case WAIT_ALWAYS:
      return true;
    default:
      // Only the Qt GUI asks for vtkGenericOpenGLRenderWindow; its servers are told.
      return !(this->InteractiveClient || vtkPVView::GetUseGenericOpenGLRenderWindow());
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::WaitForSolutionNow()
{
  vtkGlobalIlluminationFilter* filter = this->Internals->Filter;
  for (;;)
  {
    // Idle is read before the poll: a worker that publishes and goes idle after the poll
    // looked would otherwise end the wait with the previous solution drawn.
    const bool idle = !filter->GetAsynchronousBusy();
    if (filter->WaitForAsynchronousResult(0.05))
    {
      filter->Update(); // draws the new solution
    }
    if (ShowsFinal(filter) || idle)
    {
      return;
    }
    this->SetProgressText(BackgroundText(filter).c_str());
    this->UpdateProgress(filter->GetAsynchronousProgress());
  }
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetAsynchronousState()
{
  // ParaView pulls information properties from the client's own copy, whose filter has no
  // data when the server renders: a client of a remote server asks every process.
  vtkSMProxy* proxy = this->GetDisplayProxy();
  if (proxy && vtkSMSessionClient::SafeDownCast(proxy->GetSession()))
  {
    vtkNew<vtkPVGlobalIlluminationStateInformation> state;
    proxy->GatherInformation(state, vtkPVSession::CLIENT | vtkPVSession::DATA_SERVER);
    return state->GetState();
  }
  return this->GetLocalAsynchronousState();
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetLocalAsynchronousState()
{
  vtkGlobalIlluminationFilter* filter = this->Internals->Filter;
  const int shown = FieldInt(filter->GetOutputDataObject(0), "LinkGI.ShownRequest");
  if (filter->PollAsynchronousResult())
  {
    return READY;
  }
  if (filter->GetAsynchronousBusy() || static_cast<vtkTypeUInt64>(shown) < filter->GetAsynchronousRequest())
  {
    this->SetProgressText(BackgroundText(filter).c_str());
    this->UpdateProgress(filter->GetAsynchronousProgress());
    return SOLVING;
  }
  return IDLE;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::WatchForSolutions(vtkPVRenderView* view)
{
  vtkGlobalIlluminationAsyncWatcher* watcher = this->Internals->Watcher;
  vtkRenderWindowInteractor* interactor = view->GetInteractor();
  if (interactor && (watcher->GetInteractor() != interactor || watcher->GetTimerId() < 0))
  {
    watcher->Watch(interactor);
  }
}

//------------------------------------------------------------------------------
vtkSMProxy* vtkGlobalIlluminationRepresentation::GetDisplayProxy()
{
  vtkInternals& internals = *this->Internals;
  if (!internals.Proxy)
  {
    internals.Proxy = FindProxy(this);
  }
  return internals.Proxy;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::TellServersTheClientIsInteractive()
{
  // A remote server cannot see that its client is the GUI: tell it (not a state change).
  vtkInternals& internals = *this->Internals;
  if (internals.ToldServers || !vtkPVView::GetUseGenericOpenGLRenderWindow())
  {
    return;
  }
  if (vtkSMProxy* proxy = this->GetDisplayProxy())
  {
    internals.ToldServers = true;
    vtkSMPropertyHelper(proxy, "GlobalIlluminationInteractiveClient").Set(1);
    proxy->UpdateVTKObjects();
  }
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::PollForSolution()
{
  // GetAsynchronousState asks a remote server's processes too. The poll is a progress
  // request of its own, so that the progress the worker reports reaches ParaView's progress
  // bar between renders.
  vtkSMProxy* proxy = this->GetDisplayProxy();
  if (!proxy)
  {
    return vtkGlobalIlluminationAsyncWatcher::STOP;
  }
  this->TellServersTheClientIsInteractive();
  vtkSMSession* session = proxy->GetSession();
  session->PrepareProgress();
  const int state = this->GetAsynchronousState();
  session->CleanupPendingProgress();
  switch (state)
  {
    case READY:
      return vtkGlobalIlluminationAsyncWatcher::RENDER;
    case SOLVING:
      return vtkGlobalIlluminationAsyncWatcher::WAIT;
    default:
      return vtkGlobalIlluminationAsyncWatcher::STOP;
  }
}

//------------------------------------------------------------------------------
vtkDataObject* vtkGlobalIlluminationRepresentation::UpdateGlobalIllumination(
  vtkDataObject* delivered, vtkRenderer* renderer)
{
  vtkInternals& internals = *this->Internals;
  vtkGlobalIlluminationFilter* filter = internals.Filter;
  // Collective, so before anything that returns early on some processes: every process
  // renders the others' triangles into its shadow maps (exchanged when geometry changed).
  internals.GlobalCasters->Gather(delivered);
  // The filter solves all blocks as one scene; this only says what the albedo is and
  // which lights shine.
  // The albedo is what the mapper draws (UpdateColoringParameters already ran in the
  // superclass's request).
  vtkDataObject* input = internals.DrawnAlbedo->Apply(delivered, this->Mapper, this->Property, filter);
  bool emission = false;
  for (vtkDataSet* leaf : vtkCompositeDataSet::GetDataSets<vtkDataSet>(input))
  {
    emission = emission || leaf->GetPointData()->GetArray("Emission");
  }
  bool points = input && input->GetNumberOfElements(vtkDataObject::POINT) > 0;
  // In a parallel run both are the processes' together: every process takes the same
  // branch below (the filter's parallel path is collective) and an emitting partition
  // lights the others.
  AnyOverProcesses(points, emission);
  filter->SetEmissionArrayName(emission ? "Emission" : nullptr);
  this->GatherLights(renderer);

  double sky[3];
  filter->GetEnvironmentColor(sky);
  const bool dark = filter->GetNumberOfLights() == 0 && !emission && sky[0] <= 0.0 &&
    sky[1] <= 0.0 && sky[2] <= 0.0;
  if (!points || dark)
  {
    return delivered; // nothing to solve: no indirect light (the mapper draws direct light)
  }
  if (!input)
  {
    input = internals.EmptyPartition; // this process's partition is empty, others' are not
  }
  if (filter->GetInputDataObject(0, 0) != input)
  {
    filter->SetInputDataObject(input);
  }
  filter->Update(); // returns at once, with the newest finished solution
  if (this->GetWaits())
  {
    this->WaitForSolutionNow();
  }
  else if (filter->GetAsynchronousBusy())
  {
    // What ParaView's progress bar shows during this render.
    this->SetProgressText(BackgroundText(filter).c_str());
    this->UpdateProgress(filter->GetAsynchronousProgress());
  }
  vtkDataObject* output = filter->GetOutputDataObject(0);
  const int shown = FieldInt(output, "LinkGI.ShownRequest");
  const int shownStage = FieldInt(output, "LinkGI.ShownStage");
  if (!filter->GetAsynchronous())
  {
    // Synchronous (partitioned among processes): every execution is a new solution.
    if (output && output->GetMTime() != internals.SolvedTime)
    {
      internals.SolvedTime = output->GetMTime();
      ++this->NumberOfUpdates;
    }
  }
  else if (shown != 0 && (shown != internals.ShownRequest || shownStage != internals.ShownStage))
  {
    internals.ShownRequest = shown;
    internals.ShownStage = shownStage;
    ++this->NumberOfUpdates;
  }
  return output;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::GatherLights(vtkRenderer* renderer)
{
  vtkInternals& internals = *this->Internals;
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkMatrix4x4* cameraToWorld = camera->GetCameraLightTransformMatrix();

  std::size_t count = 0;
  bool keyLightTaken = false;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    const bool inspectorLight = vtkPVLight::SafeDownCast(light) != nullptr;
    if (!light->GetSwitch() || light->GetLightType() == VTK_LIGHT_TYPE_AMBIENT_LIGHT)
    {
      continue;
    }
    if (!inspectorLight)
    {
      // The light kit adds its head light, then its key light, then fill and back lights;
      // its key light is the first of its camera lights.
      if (!this->UseKeyLight || keyLightTaken || !light->LightTypeIsCameraLight())
      {
        continue;
      }
      keyLightTaken = true;
    }
    double position[3], focalPoint[3];
    light->GetPosition(position);
    light->GetFocalPoint(focalPoint);
    if (light->LightTypeIsHeadlight())
    {
      camera->GetPosition(position);
      camera->GetFocalPoint(focalPoint);
    }
    else if (light->LightTypeIsCameraLight())
    {
      // Where the renderer will place it for this frame's camera.
      Transform(cameraToWorld, position);
      Transform(cameraToWorld, focalPoint);
    }
    if (count == internals.Lights.size())
    {
      internals.Lights.push_back(vtkSmartPointer<vtkLight>::New());
    }
    // vtkLight's setters change nothing (and so trigger no update) when values are equal.
    vtkLight* copy = internals.Lights[count++];
    copy->SetLightTypeToSceneLight();
    copy->SetPositional(light->GetPositional());
    copy->SetPosition(position);
    copy->SetFocalPoint(focalPoint);
    copy->SetConeAngle(light->GetConeAngle());
    copy->SetExponent(light->GetExponent());
    if (this->LightFalloff == vtkGlobalIlluminationLights::INVERSE_SQUARE)
    {
      copy->SetAttenuationValues(0.0, 0.0, 1.0);
    }
    else
    {
      copy->SetAttenuationValues(light->GetAttenuationValues());
    }
    copy->SetDiffuseColor(light->GetDiffuseColor());
    copy->SetIntensity(light->GetIntensity());
  }
  vtkGlobalIlluminationFilter* filter = internals.Filter;
  if (static_cast<int>(count) != filter->GetNumberOfLights())
  {
    filter->RemoveAllLights();
    for (std::size_t i = 0; i < count; ++i)
    {
      filter->AddLight(internals.Lights[i]);
    }
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Use Key Light: " << (this->UseKeyLight ? "On" : "Off") << "\n";
  os << indent << "Number Of Updates: " << this->NumberOfUpdates << "\n";
  os << indent << "Wait For Solution: " << this->WaitForSolution << "\n";
  os << indent << "Interactive Client: " << (this->InteractiveClient ? "On" : "Off") << "\n";
  os << indent << "Filter:\n";
  this->Internals->Filter->PrintSelf(os, indent.GetNextIndent());
}
