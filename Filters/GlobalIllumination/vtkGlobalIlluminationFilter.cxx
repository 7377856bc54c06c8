#include "vtkGlobalIlluminationFilter.h"

#include "vtkGlobalIlluminationFilterInternals.h"

#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVersionMacros.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkGlobalIlluminationFilter);

namespace
{
/// The engine's defaults: the one place the options' default values are decided.
const linkgi::SolverOptions& EngineDefaults()
{
  static const linkgi::SolverOptions defaults;
  return defaults;
}

int ToInt(std::uint32_t value)
{
  return static_cast<int>(value);
}
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationFilter::vtkGlobalIlluminationFilter()
  : RaysPerVertex(ToInt(EngineDefaults().raysPerVertex))
  , NumberOfBounces(ToInt(EngineDefaults().bounces))
  , Method(LINKS)
  , NumberOfVPLs(ToInt(EngineDefaults().instantRadiosity.vplCount))
  , VPLClampDistance(0.02) // the engine's 0.02f, as a user types it (the float is not 0.02)
  , VPLInterleaving(ToInt(EngineDefaults().instantRadiosity.interleave))
  , VPLCompensationRays(ToInt(EngineDefaults().instantRadiosity.compensationRays))
  , ProxyVisibility(EngineDefaults().instantRadiosity.proxyVisibility ? 1 : 0)
  , ProxyResolution(ToInt(EngineDefaults().instantRadiosity.proxyResolution))
  , ImplicitVisibilityBins(ToInt(EngineDefaults().implicitVisibility.binsPerSide))
  , MaterialArrayName(nullptr)
  , IndexOfRefractionArrayName(nullptr)
  , NumberOfPhotons(ToInt(EngineDefaults().photonMapping.photons))
  , NumberOfClusters(ToInt(EngineDefaults().photonMapping.clusters))
  , FinalGatherRays(ToInt(EngineDefaults().photonMapping.gatherRays))
  , MemoryBudget(0.0)
  , ProxyVertices(0)
  , Refinement(0)
  , RefinementTolerance(0.1)
  , RefinementMaxVertices(0)
  , RefinementRounds(3)
  , FeatureAngle(EngineDefaults().featureAngleDegrees)
  , Smoothing(EngineDefaults().smoothing ? 1 : 0)
  , ComputeNormals(0)
  , Backend(AUTO)
  , AlbedoArrayName(nullptr)
  , AlbedoArrayAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS)
  , Albedo{ 0.7, 0.7, 0.7 }
  , ClampAlbedo(1)
  , EmissionArrayName(nullptr)
  , EmissionArrayAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS)
  , EnvironmentColor{ 0.0, 0.0, 0.0 }
  , EnvironmentTexture(nullptr)
  , TwoSided(EngineDefaults().twoSided ? 1 : 0)
  , Seed(ToInt(EngineDefaults().seed))
  , LightOversampling(EngineDefaults().lightOversampling ? 1 : 0)
  , Twist(EngineDefaults().twist ? 1 : 0)
  , LightIntensityScale(1.0)
  , Asynchronous(0)
  , TemporalBlend(1.0)
  , Progressive(0)
  , ProgressiveFirstStageSeconds(0.5)
  , Controller(nullptr)
  , Internals(new vtkInternals)
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationFilter::~vtkGlobalIlluminationFilter()
{
  this->SetController(nullptr);
  this->SetMaterialArrayName(nullptr);
  this->SetIndexOfRefractionArrayName(nullptr);
  this->SetAlbedoArrayName(nullptr);
  this->SetEmissionArrayName(nullptr);
  this->SetEnvironmentTexture(nullptr);
}

//------------------------------------------------------------------------------
vtkCxxSetObjectMacro(vtkGlobalIlluminationFilter, Controller, vtkMultiProcessController);

//------------------------------------------------------------------------------
int vtkGlobalIlluminationFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationFilter::FillOutputPortInformation(int, vtkInformation* info)
{
  // vtkPolyData, or a composite dataset of the input's type: see RequestDataObject.
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkDataObject");
  return 1;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkGlobalIlluminationFilter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return this->RequestDataObject(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationFilter::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A composite input gives a dataset of its type, any other input a vtkPolyData.
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  const bool composite = vtkCompositeDataSet::SafeDownCast(input) != nullptr;
  const char* wanted = composite ? input->GetClassName() : "vtkPolyData";
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* output = vtkDataObject::GetData(outInfo);
  if (!output || std::strcmp(output->GetClassName(), wanted) != 0)
  {
    outInfo->Set(vtkDataObject::DATA_OBJECT(),
      vtk::TakeSmartPointer(composite ? input->NewInstance() : vtkPolyData::New()));
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  vtkDataObject* output = vtkDataObject::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("No input: connect a vtkPolyData, another vtkDataSet or a composite dataset "
                  "to input port 0.");
    return 0;
  }

  vtkInternals& internals = *this->Internals;
  internals.Warnings.clear();
  try
  {
    vtkPolyData* surface = internals.Surface(this, input);
    // Collective under MPI, so before any branch that one process alone could take.
    vtkPolyData* solved = internals.Partitions.Gather(this->Controller, surface);
    const bool distributed = internals.Partitions.Distributed();
    if (!distributed)
    {
      internals.ActivePartition.reset();
    }
    const bool merged = surface != input;
    vtkPolyData* lit = merged ? internals.Lit.Get() : vtkPolyData::SafeDownCast(output);
    if (solved->GetNumberOfPoints() == 0) // points without cells are a point cloud: an error below
    {
      vtkWarningMacro("The input is empty; the output is empty too.");
      lit->ShallowCopy(surface);
    }
    else if (this->Asynchronous)
    {
      // Under MPI the background thread may not call MPI (pvbatch and pvserver initialise
      // it without thread support), so every process solves the whole global surface there,
      // without exchanges, and shows its own points of the newest result.
      internals.ActivePartition.reset();
      vtkPolyData* target = distributed ? internals.GlobalLit.Get() : lit;
      internals.SolveAsynchronously(this, solved, target);
      if (distributed)
      {
        internals.Partitions.Scatter(target, surface, lit);
      }
    }
    else
    {
      internals.Async.reset();
      vtkPolyData* target = distributed ? internals.GlobalLit.Get() : lit;
      // Under MPI all processes leave a failed update together (the failure anywhere in it,
      // an abort included), so none waits for another in an exchange.
      internals.Partitions.Together(this->Controller, [&] {
        const linkgi::Scene& scene = internals.UpdateScene(this, solved);
        internals.ActivePartition =
          internals.Partitions.Rows(this->Controller, internals.Mesh.ElementPoint, this->TwoSided);
        internals.Update(this, scene);
      });
      internals.ShapeOutput(solved, target);
      const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
      internals.AttachResults(this, target, elapsed.count(), internals.Solution(), internals.Stats());
      if (distributed)
      {
        internals.Partitions.Scatter(target, surface, lit);
      }
      for (const std::string& warning : internals.AllWarnings())
      {
        vtkWarningMacro(<< warning);
      }
    }
    if (merged)
    {
      internals.Merger.Deliver(lit, output);
    }
    if (!this->Asynchronous)
    {
      internals.LastOutput = vtk::TakeSmartPointer(output->NewInstance());
      internals.LastOutput->ShallowCopy(output);
    }
    return 1;
  }
  catch (const linkgi::Aborted& aborted)
  {
    vtkWarningMacro(<< aborted.what());
    this->RestorePreviousOutput(output);
    return 1;
  }
  catch (const linkgi::Error& error)
  {
    vtkErrorMacro(<< error.what());
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro("Global illumination failed: " << error.what());
  }
  this->RestorePreviousOutput(output);
  return 0;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::RestorePreviousOutput(vtkDataObject* output)
{
  const vtkDataObject* last = this->Internals->LastOutput;
  if (last && std::strcmp(last->GetClassName(), output->GetClassName()) == 0)
  {
    output->ShallowCopy(this->Internals->LastOutput);
  }
  else
  {
    output->Initialize();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::SetRaysPerVertex(int rays)
{
  const int root = std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, rays)))));
  const int square = std::min(root, 256) * std::min(root, 256);
  this->Internals->RaysRounded.clear();
  if (square != rays)
  {
    // Kept, so that every update's LinkGI.Warnings says it, not only this call's log line.
    this->Internals->RaysRounded = "RaysPerVertex must be a perfect square k*k in [1, 65536]; using " +
      std::to_string(square) + " instead of " + std::to_string(rays) + ".";
    vtkWarningMacro(<< this->Internals->RaysRounded);
  }
  if (this->RaysPerVertex != square)
  {
    this->RaysPerVertex = square;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::SetMethod(int method)
{
  if (method == this->Method)
  {
    return;
  }
  const std::vector<linkgi::Method> methods = linkgi::methods();
  if (std::find(methods.begin(), methods.end(), static_cast<linkgi::Method>(method)) != methods.end())
  {
    this->Method = method;
    this->Modified();
    return;
  }
  std::string known;
  for (const linkgi::Method m : methods)
  {
    known += (known.empty() ? "" : ", ") + std::to_string(int(m)) + " (" + linkgi::methodName(m) + ")";
  }
  vtkErrorMacro(<< "No method " << method << "; this build has " << known << ". The method stays "
                << this->GetMethodAsString() << ".");
}

//------------------------------------------------------------------------------
const char* vtkGlobalIlluminationFilter::GetMethodAsString()
{
  return linkgi::methodName(static_cast<linkgi::Method>(this->Method));
}

//------------------------------------------------------------------------------
const char* vtkGlobalIlluminationFilter::GetBackendAsString()
{
  switch (this->Backend)
  {
    case CPU:
      return "CPU";
    case CUDA:
      return "CUDA";
    default:
      return "Auto";
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::SetEnvironmentTexture(vtkImageData* texture)
{
  vtkSetObjectBodyMacro(EnvironmentTexture, vtkImageData, texture);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::AddLight(vtkLight* light)
{
  auto& lights = this->Internals->Lights;
  if (light && std::find(lights.begin(), lights.end(), light) == lights.end())
  {
    lights.emplace_back(light);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::RemoveLight(vtkLight* light)
{
  auto& lights = this->Internals->Lights;
  auto it = std::find(lights.begin(), lights.end(), light);
  if (it != lights.end())
  {
    lights.erase(it);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::RemoveAllLights()
{
  if (!this->Internals->Lights.empty())
  {
    this->Internals->Lights.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::SetLightsFromRenderer(vtkRenderer* renderer)
{
  std::vector<vtkSmartPointer<vtkLight>> lights;
  if (renderer)
  {
    vtkLightCollection* collection = renderer->GetLights();
    vtkCollectionSimpleIterator it;
    collection->InitTraversal(it);
    while (vtkLight* light = collection->GetNextLight(it))
    {
      lights.emplace_back(light);
    }
  }
  if (lights != this->Internals->Lights)
  {
    this->Internals->Lights = std::move(lights);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationFilter::GetNumberOfLights()
{
  return static_cast<int>(this->Internals->Lights.size());
}

//------------------------------------------------------------------------------
vtkLight* vtkGlobalIlluminationFilter::GetLight(int index)
{
  const auto& lights = this->Internals->Lights;
  return index >= 0 && index < static_cast<int>(lights.size()) ? lights[index].Get() : nullptr;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGlobalIlluminationFilter::GetMTime()
{
  vtkMTimeType mtime = this->Superclass::GetMTime();
  for (vtkLight* light : this->Internals->Lights)
  {
    mtime = std::max(mtime, light->GetMTime());
  }
  if (this->EnvironmentTexture)
  {
    mtime = std::max(mtime, this->EnvironmentTexture->GetMTime());
  }
  return mtime;
}

//------------------------------------------------------------------------------
// The properties as the engine's options, beside the properties' PrintSelf: a property of a
// method is declared in the header and mapped and printed here.
namespace
{
linkgi::Backend ToEngineBackend(int backend)
{
  switch (backend)
  {
    case vtkGlobalIlluminationFilter::CPU:
      return linkgi::Backend::Cpu;
    case vtkGlobalIlluminationFilter::CUDA:
      return linkgi::Backend::Cuda;
    default:
      return linkgi::Backend::Auto;
  }
}
}

linkgi::SolverOptions vtkGlobalIlluminationFilter::vtkInternals::Options(
  vtkGlobalIlluminationFilter* self)
{
  // The engine decides CPU or GPU (Auto: the GPU when a CUDA device exists) and reports the
  // choice in its stats; a CUDA request it cannot honour comes back as a warning.
  linkgi::SolverOptions options;
  options.backend = ToEngineBackend(self->Backend);
  options.raysPerVertex = static_cast<std::uint32_t>(self->RaysPerVertex);
  options.bounces = static_cast<std::uint32_t>(self->NumberOfBounces);
  options.method = static_cast<linkgi::Method>(self->Method); // SetMethod checked it
  options.partition = this->ActivePartition;
  options.photonMapping.photons = static_cast<std::uint32_t>(self->NumberOfPhotons);
  options.photonMapping.clusters = static_cast<std::uint32_t>(self->NumberOfClusters);
  options.photonMapping.gatherRays = static_cast<std::uint32_t>(self->FinalGatherRays);
  options.reference.pathsPerVertex = static_cast<std::uint32_t>(self->ReferencePathsPerVertex);
  options.implicitVisibility.binsPerSide = static_cast<std::uint32_t>(self->ImplicitVisibilityBins);
  options.memoryBudget = static_cast<std::uint64_t>(self->MemoryBudget * 1024.0 * 1024.0);
  options.instantRadiosity.vplCount = static_cast<std::uint32_t>(self->NumberOfVPLs);
  options.instantRadiosity.clampDistance = static_cast<float>(self->VPLClampDistance);
  options.instantRadiosity.interleave = static_cast<std::uint32_t>(self->VPLInterleaving);
  options.instantRadiosity.compensationRays = static_cast<std::uint32_t>(self->VPLCompensationRays);
  options.instantRadiosity.proxyVisibility = self->ProxyVisibility != 0;
  options.instantRadiosity.proxyResolution = static_cast<std::uint32_t>(self->ProxyResolution);
  options.smoothing = self->Smoothing != 0;
  options.featureAngleDegrees = static_cast<float>(self->FeatureAngle);
  options.twoSided = self->TwoSided != 0;
  options.twist = self->Twist != 0;
  options.seed = static_cast<std::uint32_t>(self->Seed);
  options.lightOversampling = self->LightOversampling != 0;
  options.albedoPolicy = self->ClampAlbedo ? linkgi::AlbedoPolicy::Clamp : linkgi::AlbedoPolicy::Reject;
  if (!this->RaysRounded.empty())
  {
    this->Warnings.push_back(this->RaysRounded); // in LinkGI.Warnings with the others
  }
  return options;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Rays Per Vertex: " << this->RaysPerVertex << "\n";
  os << indent << "Number Of Bounces: " << this->NumberOfBounces << "\n";
  os << indent << "Method: " << this->GetMethodAsString() << "\n";
  os << indent << "Number Of VPLs: " << this->NumberOfVPLs << "\n";
  os << indent << "VPL Clamp Distance: " << this->VPLClampDistance << "\n";
  os << indent << "VPL Interleaving: " << this->VPLInterleaving << "\n";
  os << indent << "VPL Compensation Rays: " << this->VPLCompensationRays << "\n";
  os << indent << "Proxy Visibility: " << (this->ProxyVisibility ? "On" : "Off") << "\n";
  os << indent << "Proxy Resolution: " << this->ProxyResolution << "\n";
  os << indent << "Implicit Visibility Bins: " << this->ImplicitVisibilityBins << "\n";
  os << indent << "Material Array Name: " << (this->MaterialArrayName ? this->MaterialArrayName : "(none)") << "\n";
  os << indent << "Index Of Refraction Array Name: "
     << (this->IndexOfRefractionArrayName ? this->IndexOfRefractionArrayName : "(none)") << "\n";
  os << indent << "Number Of Photons: " << this->NumberOfPhotons << "\n";
  os << indent << "Number Of Clusters: " << this->NumberOfClusters << "\n";
  os << indent << "Final Gather Rays: " << this->FinalGatherRays << "\n";
  os << indent << "Reference Paths Per Vertex: " << this->ReferencePathsPerVertex << "\n";
  os << indent << "Memory Budget: " << this->MemoryBudget << " MiB\n";
  os << indent << "Proxy Vertices: " << this->ProxyVertices << "\n";
  os << indent << "Refinement: " << (this->Refinement ? "On" : "Off") << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "Refinement Tolerance: " << this->RefinementTolerance << "\n";
  os << indent << "Refinement Max Vertices: " << this->RefinementMaxVertices << "\n";
  os << indent << "Refinement Rounds: " << this->RefinementRounds << "\n";
  os << indent << "Feature Angle: " << this->FeatureAngle << "\n";
  os << indent << "Smoothing: " << (this->Smoothing ? "On" : "Off") << "\n";
  os << indent << "Compute Normals: " << (this->ComputeNormals ? "On" : "Off") << "\n";
  os << indent << "Backend: " << this->GetBackendAsString() << "\n";
  os << indent << "Albedo Array Name: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)") << "\n";
  os << indent << "Albedo Array Association: "
     << (this->AlbedoArrayAssociation == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "Cells" : "Points") << "\n";
  os << indent << "Albedo: (" << this->Albedo[0] << ", " << this->Albedo[1] << ", " << this->Albedo[2] << ")\n";
  os << indent << "Clamp Albedo: " << (this->ClampAlbedo ? "On" : "Off") << "\n";
  os << indent << "Emission Array Name: " << (this->EmissionArrayName ? this->EmissionArrayName : "(none)") << "\n";
  os << indent << "Emission Array Association: "
     << (this->EmissionArrayAssociation == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "Cells" : "Points") << "\n";
  os << indent << "Environment Color: (" << this->EnvironmentColor[0] << ", "
     << this->EnvironmentColor[1] << ", " << this->EnvironmentColor[2] << ")\n";
  os << indent << "Environment Texture: " << this->EnvironmentTexture << "\n";
  os << indent << "Two Sided: " << (this->TwoSided ? "On" : "Off") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Light Oversampling: " << (this->LightOversampling ? "On" : "Off") << "\n";
  os << indent << "Twist: " << (this->Twist ? "On" : "Off") << "\n";
  os << indent << "Light Intensity Scale: " << this->LightIntensityScale << "\n";
  os << indent << "Asynchronous: " << (this->Asynchronous ? "On" : "Off") << "\n";
  os << indent << "Temporal Blend: " << this->TemporalBlend << "\n";
  os << indent << "Progressive: " << (this->Progressive ? "On" : "Off") << "\n";
  os << indent << "Progressive First Stage Seconds: " << this->ProgressiveFirstStageSeconds << "\n";
  os << indent << "Number Of Lights: " << this->Internals->Lights.size() << "\n";
}
