#include "vtkPVGlobalIlluminationFilter.h"

#include "vtkDataObject.h"
#include "vtkLight.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cstring>

namespace
{
/// ParaView's array widgets send "None" (the domain's none_string) for "no array".
const char* ArrayNameOrNull(const char* name)
{
  return (name && *name && std::strcmp(name, "None") != 0) ? name : nullptr;
}
}

vtkStandardNewMacro(vtkPVGlobalIlluminationFilter);

//------------------------------------------------------------------------------
vtkPVGlobalIlluminationFilter::vtkPVGlobalIlluminationFilter()
{
  // A scene light: its position is in world coordinates, not the camera's.
  this->PropertyLight->SetLightTypeToSceneLight();
  this->PropertyLight->SetPosition(0.0, 1.0, 0.0);
  this->PropertyLight->SetFocalPoint(0.0, 0.0, 0.0);
  this->PropertyLight->SetColor(1.0, 1.0, 1.0);
  this->PropertyLight->SetIntensity(1.0);
  // The filter's light is in physical units, as its output arrays: a point or spot light
  // falls off with 1/r^2 (vtkGlobalIlluminationLights).
  this->PropertyLight->SetAttenuationValues(0.0, 0.0, 1.0);
  this->ApplyLightType();
  this->AddLight(this->PropertyLight);
}

//------------------------------------------------------------------------------
vtkPVGlobalIlluminationFilter::~vtkPVGlobalIlluminationFilter() = default;

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::ApplyLightType()
{
  // The filter treats positional lights with a cone below 90 degrees as spot lights.
  vtkLight* light = this->PropertyLight;
  light->SetPositional(this->LightType != DIRECTIONAL_LIGHT);
  light->SetConeAngle(this->LightType == SPOT_LIGHT ? this->LightConeAngle : 180.0);
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightSwitch(vtkTypeBool on)
{
  this->PropertyLight->SetSwitch(on ? 1 : 0);
}

vtkTypeBool vtkPVGlobalIlluminationFilter::GetLightSwitch()
{
  return this->PropertyLight->GetSwitch();
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightType(int type)
{
  type = std::min(std::max(type, static_cast<int>(POINT_LIGHT)), static_cast<int>(DIRECTIONAL_LIGHT));
  if (this->LightType != type)
  {
    this->LightType = type;
    this->ApplyLightType();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightPosition(double x, double y, double z)
{
  this->PropertyLight->SetPosition(x, y, z);
}

void vtkPVGlobalIlluminationFilter::GetLightPosition(double position[3])
{
  this->PropertyLight->GetPosition(position);
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightFocalPoint(double x, double y, double z)
{
  this->PropertyLight->SetFocalPoint(x, y, z);
}

void vtkPVGlobalIlluminationFilter::GetLightFocalPoint(double focalPoint[3])
{
  this->PropertyLight->GetFocalPoint(focalPoint);
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightColor(double r, double g, double b)
{
  this->PropertyLight->SetColor(r, g, b);
}

void vtkPVGlobalIlluminationFilter::GetLightColor(double color[3])
{
  this->PropertyLight->GetDiffuseColor(color);
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightIntensity(double intensity)
{
  this->PropertyLight->SetIntensity(std::max(intensity, 0.0));
}

double vtkPVGlobalIlluminationFilter::GetLightIntensity()
{
  return this->PropertyLight->GetIntensity();
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetLightConeAngle(double angle)
{
  angle = std::min(std::max(angle, 1.0e-3), 89.0);
  if (this->LightConeAngle != angle)
  {
    this->LightConeAngle = angle;
    this->ApplyLightType();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkLight* vtkPVGlobalIlluminationFilter::GetPropertyLight()
{
  return this->PropertyLight;
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::AddAdditionalLight(vtkLight* light)
{
  this->AddLight(light);
}

void vtkPVGlobalIlluminationFilter::RemoveAllAdditionalLights()
{
  if (this->GetNumberOfLights() > 1 || this->GetLight(0) != this->PropertyLight.Get())
  {
    this->RemoveAllLights();
    this->AddLight(this->PropertyLight);
  }
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::SetAlbedoArray(
  int, int, int, int association, const char* name)
{
  this->SetAlbedoArrayAssociation(association);
  this->SetAlbedoArrayName(ArrayNameOrNull(name));
}

void vtkPVGlobalIlluminationFilter::SetEmissionArray(
  int, int, int, int association, const char* name)
{
  this->SetEmissionArrayAssociation(association);
  this->SetEmissionArrayName(ArrayNameOrNull(name));
}

void vtkPVGlobalIlluminationFilter::SetMaterialArray(int, int, int, int, const char* name)
{
  this->SetMaterialArrayName(ArrayNameOrNull(name));
}

void vtkPVGlobalIlluminationFilter::SetIndexOfRefractionArray(int, int, int, int, const char* name)
{
  this->SetIndexOfRefractionArrayName(ArrayNameOrNull(name));
}

//------------------------------------------------------------------------------
void vtkPVGlobalIlluminationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const typeNames[] = { "Point", "Spot", "Directional" };
  os << indent << "Light Type: " << typeNames[this->LightType] << "\n";
  os << indent << "Light Cone Angle: " << this->LightConeAngle << "\n";
  os << indent << "Property Light:\n";
  this->PropertyLight->PrintSelf(os, indent.GetNextIndent());
}
