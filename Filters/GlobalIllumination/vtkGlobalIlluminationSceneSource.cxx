#include "vtkGlobalIlluminationSceneSource.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "linkgi/Error.h"
#include "linkgi/Scenes.h"

#include <algorithm>
#include <cstring>

vtkStandardNewMacro(vtkGlobalIlluminationSceneSource);

namespace
{
vtkNew<vtkFloatArray> rgbArray(const char* name, const std::vector<linkgi::Vec3f>& values)
{
  vtkNew<vtkFloatArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  if (!values.empty())
  {
    std::memcpy(a->GetPointer(0), values.data(), sizeof(linkgi::Vec3f) * values.size());
  }
  return a;
}
}

vtkGlobalIlluminationSceneSource::vtkGlobalIlluminationSceneSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetSceneName("cornell");
}

vtkGlobalIlluminationSceneSource::~vtkGlobalIlluminationSceneSource()
{
  this->SetSceneName(nullptr);
}

vtkStringArray* vtkGlobalIlluminationSceneSource::GetSceneNames()
{
  vtkStringArray* names = vtkStringArray::New();
  for (const std::string& name : linkgi::standardSceneNames())
  {
    names->InsertNextValue(name);
  }
  return names;
}

bool vtkGlobalIlluminationSceneSource::MakeScene(linkgi::Scene& scene)
{
  try
  {
    linkgi::SceneParams params;
    params.deformation = static_cast<float>(this->Deformation);
    scene = linkgi::makeStandardScene(this->SceneName ? this->SceneName : "", params);
    return true;
  }
  catch (const linkgi::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
}

int vtkGlobalIlluminationSceneSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  linkgi::Scene scene;
  if (!this->MakeScene(scene))
  {
    return 0;
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(scene.vertexCount()));
  std::memcpy(points->GetVoidPointer(0), scene.positions.data(), sizeof(linkgi::Vec3f) * scene.vertexCount());
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(scene.triangleCount()), 3 * scene.triangleCount());
  for (const linkgi::Triangle& t : scene.triangles)
  {
    const vtkIdType ids[3] = { t.v[0], t.v[1], t.v[2] };
    polys->InsertNextCell(3, ids);
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  auto normals = rgbArray("Normals", scene.normals);
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(rgbArray("Albedo", scene.albedo));
  if (scene.emission.empty())
  {
    scene.emission.assign(scene.vertexCount(), linkgi::Vec3f(0.f));
  }
  output->GetPointData()->AddArray(rgbArray("Emission", scene.emission));
  if (scene.hasSpecular())
  {
    // Mirrors and glass: the filter's MaterialArrayName "Material", IndexOfRefractionArrayName
    // "IndexOfRefraction".
    vtkNew<vtkIntArray> material;
    material->SetName("Material");
    vtkNew<vtkFloatArray> ior;
    ior->SetName("IndexOfRefraction");
    for (std::size_t t = 0; t < scene.triangleCount(); ++t)
    {
      material->InsertNextValue(static_cast<int>(scene.material(t)));
      ior->InsertNextValue(scene.ior(t));
    }
    output->GetCellData()->AddArray(material);
    output->GetCellData()->AddArray(ior);
  }
  return 1;
}

void vtkGlobalIlluminationSceneSource::CreateLights(vtkLightCollection* lights)
{
  linkgi::Scene scene;
  if (!this->MakeScene(scene))
  {
    return;
  }
  for (const linkgi::Light& l : scene.lights)
  {
    vtkNew<vtkLight> light;
    const float peak = std::max(linkgi::maxComponent(l.intensity), 1e-30f);
    light->SetColor(l.intensity.x / peak, l.intensity.y / peak, l.intensity.z / peak);
    light->SetIntensity(peak);
    light->SetLightTypeToSceneLight();
    const linkgi::Vec3f d = linkgi::normalize(l.direction);
    if (l.type == linkgi::LightType::Directional)
    {
      light->SetPositional(false);
      light->SetPosition(-d.x, -d.y, -d.z);
      light->SetFocalPoint(0, 0, 0);
    }
    else
    {
      light->SetPositional(true);
      light->SetPosition(l.position.x, l.position.y, l.position.z);
      const linkgi::Vec3f f = l.position + (l.type == linkgi::LightType::Spot ? d : linkgi::Vec3f(0, -1, 0));
      light->SetFocalPoint(f.x, f.y, f.z);
      light->SetConeAngle(l.type == linkgi::LightType::Spot ? l.coneAngleDegrees : 180.0);
      light->SetExponent(l.spotExponent);
      light->SetAttenuationValues(0, 0, 1); // inverse square, as the engine
    }
    lights->AddItem(light);
  }
}

void vtkGlobalIlluminationSceneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneName: " << (this->SceneName ? this->SceneName : "(none)") << "\n";
  os << indent << "Deformation: " << this->Deformation << "\n";
}
