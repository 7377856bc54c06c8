// vtkGlobalIlluminationSceneBuilder's way back: the engine's per-element results as point
// arrays of the input, and the counters, timings and warnings as field data.
#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"
#include "vtkTypeUInt64Array.h"

//------------------------------------------------------------------------------
vtkSmartPointer<vtkFloatArray> vtkGlobalIlluminationSceneBuilder::MapToPoints(const Mesh& mesh,
  const std::vector<linkgi::Vec3f>& values, std::size_t offset, const char* name)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(mesh.InputPointCount);
  array->Fill(0.0);
  std::vector<float> copies(static_cast<std::size_t>(mesh.InputPointCount), 0.f);
  float* out = array->GetPointer(0);
  const std::size_t elements = mesh.ElementPoint.size();
  for (std::size_t e = 0; e < elements && offset + e < values.size(); ++e)
  {
    const vtkIdType p = mesh.ElementPoint[e];
    const linkgi::Vec3f& v = values[offset + e];
    out[3 * p] += v.x;
    out[3 * p + 1] += v.y;
    out[3 * p + 2] += v.z;
    copies[p] += 1.f;
  }
  for (vtkIdType p = 0; p < mesh.InputPointCount; ++p)
  {
    if (copies[p] > 1.f)
    {
      for (int k = 0; k < 3; ++k)
      {
        out[3 * p + k] /= copies[p];
      }
    }
  }
  return array;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationSceneBuilder::AddFieldValue(
  vtkFieldData* fieldData, const std::string& name, std::uint64_t value)
{
  vtkNew<vtkTypeUInt64Array> array;
  array->SetName(("LinkGI." + name).c_str());
  array->InsertNextValue(value);
  fieldData->AddArray(array);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationSceneBuilder::AddFieldValue(
  vtkFieldData* fieldData, const std::string& name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(("LinkGI." + name).c_str());
  array->InsertNextValue(value);
  fieldData->AddArray(array);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationSceneBuilder::AddFieldValue(
  vtkFieldData* fieldData, const std::string& name, const std::string& value)
{
  vtkNew<vtkStringArray> array;
  array->SetName(("LinkGI." + name).c_str());
  array->InsertNextValue(value);
  fieldData->AddArray(array);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationSceneBuilder::AddStatistics(vtkFieldData* fd,
  const linkgi::SolverStats& s, double msFilter, const std::vector<std::string>& filterWarnings)
{
  const std::pair<const char*, std::uint64_t> counters[] = { { "BvhBuilds", s.bvhBuilds },
    { "BvhRefits", s.bvhRefits }, { "Elements", s.elements }, { "Rays", s.rays },
    { "LightRays", s.lightRays }, { "HostBytesEstimated", s.hostBytesEstimated },
    { "MemoryBudget", s.memoryBudget } };
  for (const auto& c : counters)
  {
    AddFieldValue(fd, c.first, c.second);
  }
  // The method's own sizes: LinkGI.LinksCompressed, LinkGI.Vpls, ...
  for (const auto& c : s.counters)
  {
    AddFieldValue(fd, c.first, c.second);
  }
  // The method's own stages and parts: LinkGI.MsLinks, LinkGI.LinkBuilds, ...
  for (const linkgi::StageStats& stage : s.stages)
  {
    AddFieldValue(fd, "Ms" + stage.name, stage.ms);
    if (!stage.counter.empty())
    {
      AddFieldValue(fd, stage.counter, stage.runs);
    }
  }
  AddFieldValue(fd, "MsTotal", s.msTotal);
  AddFieldValue(fd, "MsFilter", msFilter);
  AddFieldValue(fd, "Method", s.method);
  // Which backend ran ("cpu" or "cuda"), on what, and why (Auto's choice or a fallback).
  AddFieldValue(fd, "Backend", s.backend);
  AddFieldValue(fd, "Device", s.device);
  AddFieldValue(fd, "BackendNote", s.backendNote);
  AddFieldValue(fd, "Gpus", static_cast<std::uint64_t>(s.devices));
  vtkNew<vtkStringArray> warnings;
  warnings->SetName("LinkGI.Warnings");
  for (const std::vector<std::string>* list : { &filterWarnings, &s.warnings })
  {
    for (const std::string& w : *list)
    {
      warnings->InsertNextValue(w);
    }
  }
  fd->AddArray(warnings);
}
