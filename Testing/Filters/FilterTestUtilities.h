// Helpers shared by the vtkGlobalIlluminationFilter tests: message capture, small meshes,
// and the conversion of an engine scene into the VTK objects the filter reads.
#pragma once

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include "linkgi/Scene.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace linkgi_test
{
/// Collects the ErrorEvent and WarningEvent messages of one object while alive (an
/// observed object prints nothing itself).
class MessageCapture
{
public:
  explicit MessageCapture(vtkObject* object)
    : Object(object)
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(&MessageCapture::OnEvent);
    this->ErrorTag = object->AddObserver(vtkCommand::ErrorEvent, this->Command);
    this->WarningTag = object->AddObserver(vtkCommand::WarningEvent, this->Command);
  }
  ~MessageCapture()
  {
    this->Object->RemoveObserver(this->ErrorTag);
    this->Object->RemoveObserver(this->WarningTag);
  }
  MessageCapture(const MessageCapture&) = delete;
  MessageCapture& operator=(const MessageCapture&) = delete;

  static bool Contains(const std::vector<std::string>& messages, const std::string& part)
  {
    for (const std::string& m : messages)
    {
      if (m.find(part) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
  bool HasError(const std::string& part) const { return Contains(this->Errors, part); }
  bool HasWarning(const std::string& part) const { return Contains(this->Warnings, part); }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }

  std::vector<std::string> Errors, Warnings;

private:
  static void OnEvent(vtkObject*, unsigned long event, void* client, void* callData)
  {
    auto* self = static_cast<MessageCapture*>(client);
    const std::string message = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings).push_back(message);
  }

  vtkObject* Object;
  vtkNew<vtkCallbackCommand> Command;
  unsigned long ErrorTag = 0, WarningTag = 0;
};

/// A `resolution` x `resolution` plane from `origin` along the edges to p1 and p2, facing
/// cross(p1 - origin, p2 - origin), with point normals.
inline vtkSmartPointer<vtkPolyData> MakePlane(const double origin[3], const double p1[3],
  const double p2[3], int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin[0], origin[1], origin[2]);
  plane->SetPoint1(p1[0], p1[1], p1[2]);
  plane->SetPoint2(p2[0], p2[1], p2[2]);
  plane->SetResolution(resolution, resolution);
  plane->Update();
  return plane->GetOutput();
}

/// The plane z = 0 over [-size, size]^2, facing +z.
inline vtkSmartPointer<vtkPolyData> MakeFloor(double size, int resolution)
{
  const double o[3] = { -size, -size, 0 }, p1[3] = { size, -size, 0 }, p2[3] = { -size, size, 0 };
  return MakePlane(o, p1, p2, resolution);
}

/// The unit cube [0,1]^3: 8 shared points, 6 outward quads, no normals.
inline vtkSmartPointer<vtkPolyData> MakeCube()
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 8; ++i)
  {
    points->InsertNextPoint(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  }
  const vtkIdType quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  vtkNew<vtkCellArray> polys;
  for (const auto& q : quads)
  {
    polys->InsertNextCell(4, q);
  }
  auto cube = vtkSmartPointer<vtkPolyData>::New();
  cube->SetPoints(points);
  cube->SetPolys(polys);
  return cube;
}

inline vtkSmartPointer<vtkFloatArray> ToArray(const std::vector<linkgi::Vec3f>& values, const char* name)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetTypedTuple(static_cast<vtkIdType>(i), &values[i].x);
  }
  return array;
}

/// The scene as a triangle vtkPolyData with point normals, an "Albedo" point array and,
/// when the scene emits, an "Emission" point array.
inline vtkSmartPointer<vtkPolyData> ToPolyData(const linkgi::Scene& scene)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  for (const linkgi::Vec3f& p : scene.positions)
  {
    points->InsertNextPoint(p.x, p.y, p.z);
  }
  vtkNew<vtkCellArray> polys;
  for (const linkgi::Triangle& t : scene.triangles)
  {
    const vtkIdType ids[3] = { t.v[0], t.v[1], t.v[2] };
    polys->InsertNextCell(3, ids);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  pd->GetPointData()->SetNormals(ToArray(scene.normals, "Normals"));
  pd->GetPointData()->AddArray(ToArray(scene.albedo, "Albedo"));
  if (!scene.emission.empty())
  {
    pd->GetPointData()->AddArray(ToArray(scene.emission, "Emission"));
  }
  return pd;
}

/// A vtkLight that the filter converts back into exactly `light` (colour carries the
/// intensity, Intensity is 1).
inline vtkSmartPointer<vtkLight> ToVtkLight(const linkgi::Light& light)
{
  auto l = vtkSmartPointer<vtkLight>::New();
  l->SetIntensity(1.0);
  l->SetDiffuseColor(light.intensity.x, light.intensity.y, light.intensity.z);
  const linkgi::Vec3f& p = light.position;
  const linkgi::Vec3f& d = light.direction;
  if (light.type == linkgi::LightType::Directional)
  {
    l->SetPositional(false);
    l->SetPosition(-d.x, -d.y, -d.z);
    l->SetFocalPoint(0, 0, 0);
    return l;
  }
  l->SetPositional(true);
  l->SetAttenuationValues(0, 0, 1); // the engine light's 1/r^2
  l->SetPosition(p.x, p.y, p.z);
  l->SetFocalPoint(double(p.x) + d.x, double(p.y) + d.y, double(p.z) + d.z);
  l->SetConeAngle(light.type == linkgi::LightType::Spot ? light.coneAngleDegrees : 90.0);
  l->SetExponent(light.spotExponent);
  return l;
}

/// A positional light at `position` shining at `focal`; point light unless `cone` < 90. A
/// lamp: it falls off with 1/r^2 (attenuation (0, 0, 1)).
inline vtkSmartPointer<vtkLight> MakeLight(const double position[3], const double focal[3],
  double intensity, bool positional = true, double cone = 90.0)
{
  auto l = vtkSmartPointer<vtkLight>::New();
  l->SetPositional(positional);
  l->SetAttenuationValues(0, 0, 1);
  l->SetPosition(position[0], position[1], position[2]);
  l->SetFocalPoint(focal[0], focal[1], focal[2]);
  l->SetConeAngle(cone);
  l->SetExponent(0.0);
  l->SetIntensity(intensity);
  l->SetDiffuseColor(1, 1, 1);
  return l;
}

/// The first tuple of field data array "LinkGI.<name>" (NaN when missing).
inline double Stat(vtkPolyData* pd, const std::string& name)
{
  vtkDataArray* array = pd->GetFieldData()->GetArray(("LinkGI." + name).c_str());
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : std::nan("");
}

inline vtkDataArray* PointArray(vtkPolyData* pd, const char* name)
{
  return pd->GetPointData()->GetArray(name);
}

/// The output's LinkGI.Warnings (empty without the array).
inline std::vector<std::string> Warnings(vtkPolyData* pd)
{
  std::vector<std::string> out;
  auto* array = vtkStringArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray("LinkGI.Warnings"));
  for (vtkIdType i = 0; array && i < array->GetNumberOfValues(); ++i)
  {
    out.push_back(array->GetValue(i));
  }
  return out;
}

/// Component c of tuple i of point array `name`.
inline double Value(vtkPolyData* pd, const char* name, vtkIdType i, int c = 0)
{
  return PointArray(pd, name)->GetComponent(i, c);
}

/// The mean of component 0 of point array `name` over the points (not area-weighted).
inline double MeanValue(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = PointArray(pd, name);
  double sum = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    sum += a->GetComponent(i, 0);
  }
  return sum / double(a->GetNumberOfTuples());
}

/// The field data's LinkGI.Method ("links", ...), empty when missing.
inline std::string MethodName(vtkPolyData* pd)
{
  auto* names = vtkStringArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray("LinkGI.Method"));
  return names && names->GetNumberOfValues() > 0 ? names->GetValue(0) : "";
}

/// A sphere (radius 0.4, centre 0.5 above the floor) over a 4 x 4 floor of
/// `floorResolution`^2 cells, with the sources' point normals.
inline vtkSmartPointer<vtkPolyData> MakeSphereOnFloor(int floorResolution = 20)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetRadius(0.4);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(MakeFloor(2, floorResolution));
  append->AddInputConnection(sphere->GetOutputPort());
  append->Update();
  return append->GetOutput();
}

/// A filter on MakeSphereOnFloor(floorResolution), lit by a point light, on the CPU.
inline vtkSmartPointer<vtkGlobalIlluminationFilter> MakeSphereOnFloorFilter(int floorResolution = 20)
{
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(MakeSphereOnFloor(floorResolution));
  const double light[3] = { 0.5, 0.3, 2.0 }, origin[3] = { 0, 0, 0 };
  filter->AddLight(MakeLight(light, origin, 4.0));
  filter->SetBackendToCPU();
  return filter;
}

/// A filter on `input` with `rays` rays per vertex, nothing else set.
inline vtkSmartPointer<vtkGlobalIlluminationFilter> MakeFilter(vtkPolyData* input, int rays = 64)
{
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(input);
  filter->SetRaysPerVertex(rays);
  return filter;
}

/// A directional light travelling straight down (-z) with irradiance `e`.
inline vtkSmartPointer<vtkLight> Sun(double e = 1.0)
{
  const double above[3] = { 0, 0, 1 }, origin[3] = { 0, 0, 0 };
  return MakeLight(above, origin, e, false);
}

/// Largest |a - b| over all components of two arrays of b's shape, relative to b's largest
/// value.
inline double RelativeDifference(vtkDataArray* a, vtkDataArray* b)
{
  double diff = 0, scale = 1e-12;
  for (vtkIdType t = 0; t < b->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < b->GetNumberOfComponents(); ++c)
    {
      const double x = a->GetComponent(t, c), y = b->GetComponent(t, c);
      diff = std::max(diff, std::abs(x - y));
      scale = std::max(scale, std::abs(y));
    }
  }
  return diff / scale;
}
}
