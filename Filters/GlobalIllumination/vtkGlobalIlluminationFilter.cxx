#include "vtkGlobalIlluminationFilter.h"

#include "vtkGlobalIlluminationBlockMerger.h"
#include "vtkGlobalIlluminationSceneBuilder.h"

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
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using Builder = vtkGlobalIlluminationSceneBuilder;

namespace
{
bool AbortRequested(vtkAlgorithm* self)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 3, 0)
  return self->CheckAbort();
#else
  return self->GetAbortExecute() != 0;
#endif
}

linkgi::Vec3f ToVec3f(const double v[3])
{
  return { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
}

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

//------------------------------------------------------------------------------
struct vtkGlobalIlluminationFilter::vtkInternals
{
  linkgi::Solver Solver;
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  vtkSmartPointer<vtkDataObject> LastOutput; // the last good output, handed out after errors
  std::vector<std::string> Warnings;         // the filter's own, for this update

  // Input that is no vtkPolyData (composite, or another dataset) is merged into one
  // surface, lit as `Lit`, and delivered back onto its blocks.
  vtkGlobalIlluminationBlockMerger Merger;
  vtkNew<vtkPolyData> Lit;
  vtkPolyData* Surface(vtkGlobalIlluminationFilter* self, vtkDataObject* input);

  // The triangle mesh and what it was built from; rebuilt only when one of these changes,
  // so a light-only update costs no triangulation.
  Builder::Mesh Mesh;
  bool MeshValid = false;
  const vtkPolyData* MeshInput = nullptr;
  vtkMTimeType MeshInputTime = 0;
  bool MeshComputeNormals = false;
  double MeshFeatureAngle = 0.0;

  const linkgi::Scene& UpdateScene(vtkGlobalIlluminationFilter* self, vtkPolyData* input);
  linkgi::SolverOptions Options(vtkGlobalIlluminationFilter* self);
  linkgi::ProgressCallback Progress(vtkGlobalIlluminationFilter* self);
  void AttachResults(vtkGlobalIlluminationFilter* self, vtkPolyData* output, double msFilter,
    const linkgi::Solution& solution, const linkgi::SolverStats& stats);

  // Asynchronous mode: the worker, and the request whose result the output shows.
  std::unique_ptr<linkgi::AsyncSolver> Async;
  std::uint64_t ShownRequest = 0;
  bool SolveAsynchronously(vtkGlobalIlluminationFilter* self, vtkPolyData* input, vtkPolyData* output);

  /// The filter's warnings of this update, then the engine's.
  std::vector<std::string> AllWarnings() const
  {
    std::vector<std::string> all = this->Warnings;
    const auto& engine = this->Solver.stats().warnings;
    all.insert(all.end(), engine.begin(), engine.end());
    return all;
  }
};

//------------------------------------------------------------------------------
const linkgi::Scene& vtkGlobalIlluminationFilter::vtkInternals::UpdateScene(
  vtkGlobalIlluminationFilter* self, vtkPolyData* input)
{
  const bool computeNormals = self->ComputeNormals != 0;
  const bool stale = !this->MeshValid || this->MeshInput != input ||
    this->MeshInputTime != input->GetMTime() || this->MeshComputeNormals != computeNormals ||
    (this->Mesh.NormalsComputed && this->MeshFeatureAngle != self->FeatureAngle);
  if (stale)
  {
    this->MeshValid = false;
    this->Mesh = Builder::BuildMesh(input, computeNormals, self->FeatureAngle);
    this->MeshInput = input;
    this->MeshInputTime = input->GetMTime();
    this->MeshComputeNormals = computeNormals;
    this->MeshFeatureAngle = self->FeatureAngle;
    this->MeshValid = true;
  }

  linkgi::Scene& scene = this->Mesh.Scene;
  scene.albedo = Builder::GatherColors(input, this->Mesh, self->AlbedoArrayName,
    self->AlbedoArrayAssociation, ToVec3f(self->Albedo), "albedo");
  scene.emission.clear();
  if (self->EmissionArrayName && *self->EmissionArrayName)
  {
    scene.emission = Builder::GatherColors(input, this->Mesh, self->EmissionArrayName,
      self->EmissionArrayAssociation, linkgi::Vec3f(0.f), "emission");
  }
  scene.lights.clear();
  for (vtkLight* light : this->Lights)
  {
    linkgi::Light converted;
    const auto status = Builder::ConvertLight(light, self->LightIntensityScale, converted);
    if (status == vtkGlobalIlluminationLights::CONVERTED)
    {
      scene.lights.push_back(converted);
    }
    const std::string skipped = vtkGlobalIlluminationLights::Explain(status, light);
    if (!skipped.empty())
    {
      this->Warnings.push_back(skipped);
    }
  }
  scene.environment = Builder::ConvertEnvironment(self->EnvironmentColor, self->EnvironmentTexture);
  if (self->EnvironmentTexture && scene.environment.color == linkgi::Vec3f(0.f))
  {
    this->Warnings.emplace_back("EnvironmentTexture is set but EnvironmentColor is black, "
                                "so the sky is black; set EnvironmentColor to 1,1,1.");
  }
  return scene;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkGlobalIlluminationFilter::vtkInternals::Surface(
  vtkGlobalIlluminationFilter* self, vtkDataObject* input)
{
  if (auto poly = vtkPolyData::SafeDownCast(input))
  {
    return poly;
  }
  // The merged surface carries the colour arrays under their names, with the constant
  // albedo (or no emission) for blocks that lack them, so UpdateScene reads it as it reads
  // a vtkPolyData.
  std::vector<vtkGlobalIlluminationBlockMerger::Carried> carried;
  if (self->AlbedoArrayName && *self->AlbedoArrayName)
  {
    carried.push_back({ self->AlbedoArrayName, self->AlbedoArrayAssociation,
      { { self->Albedo[0], self->Albedo[1], self->Albedo[2] } }, "albedo" });
  }
  if (self->EmissionArrayName && *self->EmissionArrayName)
  {
    carried.push_back({ self->EmissionArrayName, self->EmissionArrayAssociation,
      { { 0.0, 0.0, 0.0 } }, "emission" });
  }
  this->Merger.Merge(input, carried);
  return this->Merger.GetMerged();
}

//------------------------------------------------------------------------------
linkgi::SolverOptions vtkGlobalIlluminationFilter::vtkInternals::Options(
  vtkGlobalIlluminationFilter* self)
{
  // The engine decides CPU or GPU (Auto: the GPU when a CUDA device exists) and reports the
  // choice in its stats; a CUDA request it cannot honour comes back as a warning.
  linkgi::SolverOptions options;
  options.backend = ToEngineBackend(self->Backend);
  options.raysPerVertex = static_cast<std::uint32_t>(self->RaysPerVertex);
  options.bounces = static_cast<std::uint32_t>(self->NumberOfBounces);
  options.smoothing = self->Smoothing != 0;
  options.featureAngleDegrees = static_cast<float>(self->FeatureAngle);
  options.twoSided = self->TwoSided != 0;
  options.twist = self->Twist != 0;
  options.seed = static_cast<std::uint32_t>(self->Seed);
  options.lightOversampling = self->LightOversampling != 0;
  options.albedoPolicy = self->ClampAlbedo ? linkgi::AlbedoPolicy::Clamp : linkgi::AlbedoPolicy::Reject;
  return options;
}

//------------------------------------------------------------------------------
linkgi::ProgressCallback vtkGlobalIlluminationFilter::vtkInternals::Progress(
  vtkGlobalIlluminationFilter* self)
{
  struct State
  {
    std::string Stage;
    double Last = 0.0;
  };
  auto state = std::make_shared<State>();
  // The engine calls this on this thread between chunks of work (so VTK events may fire
  // here) with the fraction of the whole update done.
  return [self, state](const char* stage, double fraction) {
    if (state->Stage != stage)
    {
      state->Stage = stage;
      self->SetProgressText(stage);
    }
    if (fraction > state->Last)
    {
      state->Last = fraction;
      self->UpdateProgress(std::min(fraction, 1.0));
    }
    return !AbortRequested(self);
  };
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::vtkInternals::AttachResults(vtkGlobalIlluminationFilter* self,
  vtkPolyData* output, double msFilter, const linkgi::Solution& solution,
  const linkgi::SolverStats& s)
{
  const std::size_t elements = this->Mesh.ElementPoint.size();
  vtkPointData* pd = output->GetPointData();
  for (std::size_t side = 0; side < (self->TwoSided ? 2 : 1); ++side)
  {
    const std::string suffix = side ? "Back" : "";
    const std::size_t offset = side * elements;
    pd->AddArray(Builder::MapToPoints(this->Mesh, solution.direct, offset, ("DirectIrradiance" + suffix).c_str()));
    pd->AddArray(Builder::MapToPoints(this->Mesh, solution.indirect, offset, ("IndirectIrradiance" + suffix).c_str()));
    pd->AddArray(Builder::MapToPoints(this->Mesh, solution.radiance, offset, ("Radiance" + suffix).c_str()));
  }

  Builder::AddStatistics(output->GetFieldData(), s, msFilter, this->Warnings);
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationFilter::vtkInternals::SolveAsynchronously(
  vtkGlobalIlluminationFilter* self, vtkPolyData* input, vtkPolyData* output)
{
  const auto start = std::chrono::steady_clock::now();
  if (!this->Async)
  {
    this->Async = std::make_unique<linkgi::AsyncSolver>();
  }
  this->Async->setBlend(static_cast<float>(self->TemporalBlend));
  // Returns at once; repeating the request of the scene already solved starts nothing.
  this->Async->request(this->UpdateScene(self, input), this->Options(self));
  output->ShallowCopy(input);
  const std::string error = this->Async->lastError();
  if (!error.empty())
  {
    this->Warnings.push_back("The last asynchronous update failed: " + error);
  }
  const std::shared_ptr<const linkgi::AsyncResult> latest = this->Async->latest();
  const std::size_t elements = this->Mesh.ElementPoint.size() * (self->TwoSided ? 2 : 1);
  linkgi::Solution shown;
  linkgi::SolverStats stats;
  if (latest && latest->solution.elementCount() == elements)
  {
    // The newest finished result for a mesh of this size: possibly one update behind.
    shown = latest->solution;
    stats = latest->stats;
    this->ShownRequest = latest->request;
  }
  else
  {
    // Nothing solved for this mesh yet: black, until the worker delivers.
    shown.direct.assign(elements, linkgi::Vec3f(0.f));
    shown.indirect = shown.radiance = shown.direct;
  }
  const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
  this->AttachResults(self, output, elapsed.count(), shown, stats);
  Builder::AddFieldValue(output->GetFieldData(), "Pending", std::uint64_t(this->Async->busy() ? 1 : 0));
  Builder::AddFieldValue(output->GetFieldData(), "ShownRequest", this->ShownRequest);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationFilter::PollAsynchronousResult()
{
  const auto& async = this->Internals->Async;
  const auto latest = async ? async->latest() : nullptr;
  if (!latest || latest->request == this->Internals->ShownRequest)
  {
    return false;
  }
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkGlobalIlluminationFilter);

//------------------------------------------------------------------------------
vtkGlobalIlluminationFilter::vtkGlobalIlluminationFilter()
  : RaysPerVertex(256)
  , NumberOfBounces(3)
  , FeatureAngle(30.0)
  , Smoothing(1)
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
  , TwoSided(0)
  , Seed(0)
  , LightOversampling(1)
  , Twist(1)
  , LightIntensityScale(1.0)
  , Asynchronous(0)
  , TemporalBlend(1.0)
  , Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationFilter::~vtkGlobalIlluminationFilter()
{
  this->SetAlbedoArrayName(nullptr);
  this->SetEmissionArrayName(nullptr);
  this->SetEnvironmentTexture(nullptr);
}

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
    const bool merged = surface != input;
    vtkPolyData* lit = merged ? internals.Lit.Get() : vtkPolyData::SafeDownCast(output);
    if (surface->GetNumberOfPoints() == 0 || surface->GetNumberOfCells() == 0)
    {
      vtkWarningMacro("The input is empty; the output is empty too.");
      lit->ShallowCopy(surface);
    }
    else if (this->Asynchronous)
    {
      internals.SolveAsynchronously(this, surface, lit);
    }
    else
    {
      internals.Async.reset();
      const linkgi::Scene& scene = internals.UpdateScene(this, surface);
      internals.Solver.update(scene, internals.Options(this), internals.Progress(this));
      lit->ShallowCopy(surface);
      const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
      internals.AttachResults(
        this, lit, elapsed.count(), internals.Solver.solution(), internals.Solver.stats());
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
  if (square != rays)
  {
    vtkWarningMacro("RaysPerVertex must be a perfect square k*k in [1, 65536]; using "
      << square << " instead of " << rays << ".");
  }
  if (this->RaysPerVertex != square)
  {
    this->RaysPerVertex = square;
    this->Modified();
  }
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
void vtkGlobalIlluminationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Rays Per Vertex: " << this->RaysPerVertex << "\n";
  os << indent << "Number Of Bounces: " << this->NumberOfBounces << "\n";
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
  os << indent << "Number Of Lights: " << this->Internals->Lights.size() << "\n";
}
