#include "vtkGlobalIlluminationFilterInternals.h"

#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationGeometry.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkVersionMacros.h"

#include "linkgi/Error.h"
#include "linkgi/Memory.h"
#include "linkgi/Orientation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

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

// The colour array `name` of `input` as GatherColors reads it, or null.
vtkObject* ColorArray(vtkPolyData* input, const char* name, int association)
{
  if (!name || !*name)
  {
    return nullptr;
  }
  return association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? input->GetCellData()->GetAbstractArray(name)
                                                               : input->GetPointData()->GetAbstractArray(name);
}

}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationSourceKey::Set(const std::vector<vtkObject*>& objects)
{
  this->Objects.assign(objects.begin(), objects.end());
  this->Times.clear();
  for (vtkObject* object : objects)
  {
    this->Times.push_back(object ? object->GetMTime() : 0);
  }
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationSourceKey::Matches(const std::vector<vtkObject*>& objects) const
{
  if (objects.size() != this->Objects.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < objects.size(); ++i)
  {
    // A dead object's weak pointer is null: it matches no live one.
    vtkObject* object = objects[i];
    if (this->Objects[i].GetPointer() != object || (object ? object->GetMTime() : 0) != this->Times[i])
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
const linkgi::Scene& vtkGlobalIlluminationFilter::vtkInternals::UpdateScene(
  vtkGlobalIlluminationFilter* self, vtkPolyData* input)
{
  const bool computeNormals = self->ComputeNormals != 0;
  const std::vector<vtkObject*> geometry = vtkGlobalIlluminationGeometry::Sources(input);
  const bool stale = !this->MeshSource.Matches(geometry) ||
    this->MeshComputeNormals != computeNormals ||
    (this->Mesh.NormalsComputed && this->MeshFeatureAngle != self->FeatureAngle);
  if (stale)
  {
    this->MeshSource.Clear();
    this->Mesh = Builder::BuildMesh(input, computeNormals, self->FeatureAngle);
    ++this->MeshVersion;
    this->MeshSource.Set(geometry);
    this->MeshComputeNormals = computeNormals;
    this->MeshFeatureAngle = self->FeatureAngle;
  }

  linkgi::Scene& scene = this->Mesh.Scene;
  char albedo[128];
  std::snprintf(albedo, sizeof(albedo), "%a %a %a", self->Albedo[0], self->Albedo[1], self->Albedo[2]);
  const auto name = [](const char* s) { return std::string(s ? s : ""); };
  const std::string colorsKey = std::to_string(this->MeshVersion) + '|' +
    name(self->AlbedoArrayName) + '|' + std::to_string(self->AlbedoArrayAssociation) + '|' +
    albedo + '|' + name(self->EmissionArrayName) + '|' +
    std::to_string(self->EmissionArrayAssociation);
  const std::vector<vtkObject*> colorArrays = {
    ColorArray(input, self->AlbedoArrayName, self->AlbedoArrayAssociation),
    ColorArray(input, self->EmissionArrayName, self->EmissionArrayAssociation)
  };
  // The mesh (its input), the colour settings or the colour arrays changed.
  if (colorsKey != this->ColorsKey || !this->ColorsSource.Matches(colorArrays))
  {
    this->ColorsKey.clear();
    scene.albedo = Builder::GatherColors(input, this->Mesh, self->AlbedoArrayName,
      self->AlbedoArrayAssociation, ToVec3f(self->Albedo), "albedo");
    scene.emission.clear();
    if (self->EmissionArrayName && *self->EmissionArrayName)
    {
      scene.emission = Builder::GatherColors(input, this->Mesh, self->EmissionArrayName,
        self->EmissionArrayAssociation, linkgi::Vec3f(0.f), "emission");
    }
    this->ColorsKey = colorsKey;
    this->ColorsSource.Set(colorArrays);
  }
  scene.triangleMaterials.clear();
  scene.triangleIor.clear();
  if (self->MaterialArrayName && *self->MaterialArrayName)
  {
    const std::vector<double> values =
      Builder::GatherTriangleValues(input, this->Mesh, self->MaterialArrayName, true, "material");
    scene.triangleMaterials.resize(values.size());
    for (std::size_t t = 0; t < values.size(); ++t)
    {
      if (!(values[t] == 0.0 || values[t] == 1.0 || values[t] == 2.0))
      {
        throw linkgi::Error("The material array '" + std::string(self->MaterialArrayName) + "' has the value " +
          std::to_string(values[t]) + "; the materials are 0 (diffuse), 1 (mirror) and 2 (glass).");
      }
      scene.triangleMaterials[t] = static_cast<linkgi::MaterialType>(int(values[t]));
    }
  }
  if (self->IndexOfRefractionArrayName && *self->IndexOfRefractionArrayName)
  {
    const std::vector<double> values = Builder::GatherTriangleValues(
      input, this->Mesh, self->IndexOfRefractionArrayName, false, "index of refraction");
    scene.triangleIor.assign(values.begin(), values.end()); // the engine checks each value
  }
  scene.lights.clear();
  for (vtkLight* light : this->Lights)
  {
    linkgi::Light converted;
    const auto status = Builder::ConvertLight(light, self->LightIntensityScale, this->Mesh.Origin, converted);
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
  this->Warnings.insert(this->Warnings.end(), this->Mesh.Warnings.begin(), this->Mesh.Warnings.end());
  for (std::string& turned : Builder::OrientToLights(this->Mesh, !self->TwoSided))
  {
    this->Warnings.push_back(std::move(turned));
  }
  if (!self->TwoSided && linkgi::litOnlyFromBehind(scene))
  {
    this->Warnings.emplace_back("Every light is behind the surface (on the side its normals point "
                                "away from), so it receives no direct light. Turn TwoSided on to "
                                "light both sides, or reverse the normals (vtkReverseSense).");
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
  if (self->Refinement)
  {
    throw linkgi::Error(std::string("Refinement needs a vtkPolyData input (its output is a new "
                                    "surface); this input is a ") + input->GetClassName() +
      ". Extract its surface first, or switch Refinement off.");
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
linkgi::ResolutionOptions vtkGlobalIlluminationFilter::vtkInternals::Resolution(
  vtkGlobalIlluminationFilter* self) const
{
  if (self->ProxyVertices < 0)
  {
    throw linkgi::Error("ProxyVertices must be 0 (no proxy) or a vertex count smaller than the "
                        "input's; got " + std::to_string(self->ProxyVertices) + ".");
  }
  if (self->RefinementMaxVertices < 0)
  {
    throw linkgi::Error("RefinementMaxVertices must be 0 (four times the input) or a vertex "
                        "count; got " + std::to_string(self->RefinementMaxVertices) + ".");
  }
  linkgi::ResolutionOptions resolution;
  resolution.proxyVertices = static_cast<std::size_t>(self->ProxyVertices);
  resolution.refine = self->Refinement != 0;
  resolution.refinement.tolerance = static_cast<float>(self->RefinementTolerance);
  resolution.refinement.rounds = static_cast<std::uint32_t>(std::max(self->RefinementRounds, 0));
  resolution.refinement.maxVertices = static_cast<std::size_t>(self->RefinementMaxVertices);
  return resolution;
}

void vtkGlobalIlluminationFilter::vtkInternals::Update(
  vtkGlobalIlluminationFilter* self, const linkgi::Scene& scene)
{
  this->Solver.update(scene, this->Options(self), this->Resolution(self), this->Progress(self));
  this->RefinedUsed = this->Solver.refined() != nullptr;
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
namespace
{
// The result arrays' names, front sides; the back sides' add "Back".
constexpr const char* DirectName = "DirectIrradiance";
constexpr const char* IndirectName = "IndirectIrradiance";
constexpr const char* RadianceName = "Radiance";
constexpr const char* CausticName = "CausticIrradiance";
}

bool vtkGlobalIlluminationFilter::IsResultArray(const char* name)
{
  if (!name)
  {
    return false;
  }
  std::string front(name);
  if (front.size() > 4 && front.compare(front.size() - 4, 4, "Back") == 0)
  {
    front.resize(front.size() - 4);
  }
  return front == DirectName || front == IndirectName || front == RadianceName ||
    front == CausticName;
}

//------------------------------------------------------------------------------
std::vector<vtkSmartPointer<vtkDataArray>> vtkGlobalIlluminationFilter::vtkInternals::PointArrays(
  vtkGlobalIlluminationFilter* self, const linkgi::Solution& solution)
{
  const Builder::Mesh& mesh = this->RefinedUsed ? this->RefinedMesh : this->Mesh;
  const std::size_t elements = mesh.ElementPoint.size();
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  for (std::size_t side = 0; side < (self->TwoSided ? 2 : 1); ++side)
  {
    const std::string suffix = side ? "Back" : "";
    const std::size_t offset = side * elements;
    arrays.push_back(Builder::MapToPoints(mesh, solution.direct, offset, (DirectName + suffix).c_str()));
    arrays.push_back(Builder::MapToPoints(mesh, solution.indirect, offset, (IndirectName + suffix).c_str()));
    arrays.push_back(Builder::MapToPoints(mesh, solution.radiance, offset, (RadianceName + suffix).c_str()));
    if (!solution.caustics.empty())
    {
      arrays.push_back(Builder::MapToPoints(mesh, solution.caustics, offset, (CausticName + suffix).c_str()));
    }
  }
  return arrays;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::vtkInternals::AttachResults(vtkGlobalIlluminationFilter* self,
  vtkPolyData* output, double msFilter, const linkgi::Solution& solution,
  const linkgi::SolverStats& s)
{
  for (const auto& array : this->PointArrays(self, solution))
  {
    output->GetPointData()->AddArray(array);
  }
  Builder::AddStatistics(output->GetFieldData(), s, msFilter, this->Warnings);
  this->AddLamps(output);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::vtkInternals::AddLamps(vtkPolyData* output) const
{
  // Whether a light is a lamp, which picks the lamp look wherever the result is displayed
  // without the lights (vtkGlobalIlluminationDisplayColors, the exporters).
  bool lamps = false;
  for (const auto& light : this->Lights)
  {
    vtkGlobalIlluminationLights::Light converted;
    lamps = lamps ||
      (vtkGlobalIlluminationLights::Convert(light, 1.0, converted) ==
          vtkGlobalIlluminationLights::CONVERTED &&
        converted.FallsOff());
  }
  Builder::AddFieldValue(output->GetFieldData(), "Lamps", static_cast<std::uint64_t>(lamps));
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationFilter::vtkInternals::SolveAsynchronously(
  vtkGlobalIlluminationFilter* self, vtkPolyData* input, vtkPolyData* output)
{
  const auto start = std::chrono::steady_clock::now();
  this->RefinedUsed = false;
  if (!this->Async)
  {
    this->Async = std::make_unique<linkgi::AsyncSolver>();
  }
  this->Async->setBlend(static_cast<float>(self->TemporalBlend));
  this->Async->setProgressive(self->Progressive != 0);
  this->Async->setFirstStageSeconds(self->ProgressiveFirstStageSeconds);
  // Returns at once; repeating the request of the scene already solved starts nothing.
  this->LastRequest =
    this->Async->request(this->UpdateScene(self, input), this->Options(self), this->Resolution(self));
  output->ShallowCopy(input);
  const std::string error = this->Async->lastError();
  if (!error.empty())
  {
    this->Warnings.push_back("The last asynchronous update failed: " + error);
  }
  std::shared_ptr<const linkgi::AsyncResult> latest = this->Async->latest();
  const std::size_t elements = this->Mesh.ElementPoint.size() * (self->TwoSided ? 2 : 1);
  if (latest && latest->solution.elementCount() == elements)
  {
    this->ShownRequest = latest->request; // possibly one update behind the newest request
    this->ShownStage = latest->stage;
  }
  else
  {
    latest.reset(); // nothing solved for this mesh yet: black, until the worker delivers
  }
  ShownArrays& shown = this->Shown;
  const bool twoSided = self->TwoSided != 0;
  if (shown.Arrays.empty() || shown.Result != latest || shown.MeshVersion != this->MeshVersion ||
    shown.TwoSided != twoSided)
  {
    linkgi::Solution black;
    if (!latest)
    {
      black.direct.assign(elements, linkgi::Vec3f(0.f));
      black.indirect = black.radiance = black.direct;
    }
    shown.Arrays = this->PointArrays(self, latest ? latest->solution : black);
    shown.Result = latest;
    shown.MeshVersion = this->MeshVersion;
    shown.TwoSided = twoSided;
  }
  for (const auto& array : shown.Arrays)
  {
    output->GetPointData()->AddArray(array);
  }
  const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
  Builder::AddStatistics(output->GetFieldData(), latest ? latest->stats : linkgi::SolverStats(),
    elapsed.count(), this->Warnings);
  this->AddLamps(output);
  // A render loop runs this at every frame: each warning goes to the log (and ParaView's
  // output messages) when it first appears, not at every frame while it holds.
  std::vector<std::string> now = this->Warnings;
  if (latest)
  {
    now.insert(now.end(), latest->stats.warnings.begin(), latest->stats.warnings.end());
  }
  for (const std::string& warning : now)
  {
    if (std::find(this->Announced.begin(), this->Announced.end(), warning) == this->Announced.end())
    {
      vtkWarningWithObjectMacro(self, << warning);
    }
  }
  this->Announced = std::move(now);
  Builder::AddFieldValue(output->GetFieldData(), "Pending", std::uint64_t(this->Async->busy() ? 1 : 0));
  Builder::AddFieldValue(output->GetFieldData(), "ShownRequest", this->ShownRequest);
  Builder::AddFieldValue(output->GetFieldData(), "ShownStage", std::uint64_t(latest ? latest->stage : 0));
  Builder::AddFieldValue(output->GetFieldData(), "Stages", std::uint64_t(latest ? latest->stages : 0));
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationFilter::vtkInternals::ShapeOutput(vtkPolyData* input, vtkPolyData* output)
{
  if (!this->RefinedUsed)
  {
    output->ShallowCopy(input);
    return;
  }
  // One output point per element of the refined scene: the input's elements first (their
  // input points' data), then the midpoints in order (their two parents' mean).
  const linkgi::RefinedScene& refined = *this->Solver.refined();
  const linkgi::Scene& scene = refined.scene;
  const vtkIdType n = static_cast<vtkIdType>(scene.vertexCount());
  vtkNew<vtkPoints> points;
  points->SetDataType(input->GetPoints()->GetDataType()); // double stays double (UTM data)
  points->SetNumberOfPoints(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    const linkgi::Vec3f& p = scene.positions[static_cast<std::size_t>(v)];
    const std::array<double, 3>& o = this->Mesh.Origin;
    points->SetPoint(v, o[0] + p.x, o[1] + p.y, o[2] + p.z);
  }
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(scene.triangleCount()), 3 * static_cast<vtkIdType>(scene.triangleCount()));
  for (const linkgi::Triangle& t : scene.triangles)
  {
    const vtkIdType ids[3] = { t.v[0], t.v[1], t.v[2] };
    polys->InsertNextCell(3, ids);
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetFieldData()->ShallowCopy(input->GetFieldData());

  vtkPointData* inPoints = input->GetPointData();
  vtkPointData* outPoints = output->GetPointData();
  outPoints->CopyAllocate(inPoints, n);
  const std::size_t first = refined.inputVertices;
  for (std::size_t v = 0; v < first; ++v)
  {
    outPoints->CopyData(inPoints, this->Mesh.ElementPoint[v], static_cast<vtkIdType>(v));
  }
  for (int a = 0; a < outPoints->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = outPoints->GetAbstractArray(a);
    array->SetNumberOfTuples(n);
    for (std::size_t k = 0; k < refined.midpointOf.size(); ++k)
    {
      array->InterpolateTuple(static_cast<vtkIdType>(first + k), refined.midpointOf[k][0], array,
        refined.midpointOf[k][1], array, 0.5);
    }
  }
  // The normals the light was solved with: the input's, or those computed for it (then a
  // new array), at its points; their edge ends' normalized mean at the new points. Without
  // them a refined surface would be shaded with normals of its own faces.
  vtkDataArray* normals = outPoints->GetNormals();
  vtkIdType from = static_cast<vtkIdType>(first);
  if (this->Mesh.NormalsComputed)
  {
    vtkNew<vtkFloatArray> computed;
    computed->SetName("Normals");
    computed->SetNumberOfComponents(3);
    computed->SetNumberOfTuples(n);
    outPoints->SetNormals(computed);
    normals = computed;
    from = 0;
  }
  if (normals)
  {
    for (vtkIdType v = from; v < n; ++v)
    {
      const linkgi::Vec3f& nv = scene.normals[static_cast<std::size_t>(v)];
      normals->SetTuple3(v, nv.x, nv.y, nv.z);
    }
  }
  vtkCellData* inCells = input->GetCellData();
  vtkCellData* outCells = output->GetCellData();
  const vtkIdType triangles = static_cast<vtkIdType>(scene.triangleCount());
  outCells->CopyAllocate(inCells, triangles);
  for (vtkIdType t = 0; t < triangles; ++t)
  {
    outCells->CopyData(inCells, this->Mesh.TriangleCell[refined.sourceTriangle[static_cast<std::size_t>(t)]], t);
  }

  this->RefinedMesh.ElementPoint.resize(static_cast<std::size_t>(n));
  std::iota(this->RefinedMesh.ElementPoint.begin(), this->RefinedMesh.ElementPoint.end(), vtkIdType(0));
  this->RefinedMesh.InputPointCount = n;
}
