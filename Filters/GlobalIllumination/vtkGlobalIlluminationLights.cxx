#include "vtkGlobalIlluminationLights.h"

#include "vtkLight.h"
#include "vtkMath.h"

#include <cmath>
#include <sstream>

//------------------------------------------------------------------------------
double vtkGlobalIlluminationLights::Light::CosCone() const
{
  return std::cos(vtkMath::RadiansFromDegrees(this->ConeAngle));
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationLights::Light::FallsOff() const
{
  return this->Type != DIRECTIONAL && (this->Attenuation[1] > 0.0 || this->Attenuation[2] > 0.0);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationLights::MakeLamp(vtkLight* light)
{
  light->SetPositional(true);
  light->SetAttenuationValues(0.0, 0.0, 1.0);
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationLights::Status vtkGlobalIlluminationLights::Convert(
  vtkLight* light, double scale, Light& out, int falloff)
{
  if (!light || !light->GetSwitch())
  {
    return SWITCHED_OFF;
  }
  double position[3], focal[3], color[3];
  light->GetTransformedPosition(position);
  light->GetTransformedFocalPoint(focal);
  light->GetDiffuseColor(color);
  double axis[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const bool hasAxis = vtkMath::Normalize(axis) > 0.0;

  Light result;
  if (light->GetPositional())
  {
    result.Type = light->GetConeAngle() < 90.0 ? Light::SPOT : Light::POINT;
    result.ConeAngle = light->GetConeAngle();
    result.Exponent = light->GetExponent();
    light->GetAttenuationValues(result.Attenuation.data());
    if (falloff == INVERSE_SQUARE)
    {
      result.Attenuation = { { 0.0, 0.0, 1.0 } };
    }
    const auto& a = result.Attenuation;
    const bool valid = a[0] >= 0.0 && a[1] >= 0.0 && a[2] >= 0.0 && a[0] + a[1] + a[2] > 0.0 &&
      std::isfinite(a[0] + a[1] + a[2]);
    if (!valid)
    {
      return NOT_PHYSICAL;
    }
  }
  else
  {
    result.Type = Light::DIRECTIONAL;
  }
  if (result.Type != Light::POINT && !hasAxis)
  {
    return NO_DIRECTION;
  }
  const double power = light->GetIntensity() * scale;
  for (int k = 0; k < 3; ++k)
  {
    result.Position[k] = position[k];
    result.Intensity[k] = color[k] * power;
    if (hasAxis)
    {
      result.Direction[k] = axis[k];
    }
    const bool physical = result.Intensity[k] >= 0.0 && std::isfinite(result.Intensity[k]) &&
      std::isfinite(position[k]) && std::isfinite(focal[k]);
    if (!physical)
    {
      return NOT_PHYSICAL;
    }
  }
  out = result;
  return CONVERTED;
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationLights::Explain(Status status, vtkLight* light)
{
  if (status != NO_DIRECTION && status != NOT_PHYSICAL)
  {
    return std::string();
  }
  double position[3];
  light->GetTransformedPosition(position);
  std::ostringstream msg;
  if (status == NOT_PHYSICAL)
  {
    double color[3];
    light->GetDiffuseColor(color);
    msg << "A light (vtkLight " << static_cast<const void*>(light) << ") has a negative or "
        << "non-finite colour x intensity (" << color[0] << ", " << color[1] << ", " << color[2]
        << ") x " << light->GetIntensity() << ", a non-finite position or focal point, "
        << "or attenuation values that are negative or all zero, so it is skipped; give it a "
        << "colour and an intensity of 0 or more, and attenuation (1, 0, 0) for no distance "
        << "falloff or (0, 0, 1) for 1/r^2.";
    return msg.str();
  }
  msg << "A " << (light->GetPositional() ? "spot" : "directional") << " light (vtkLight "
      << static_cast<const void*>(light) << ") has its focal point at its position ("
      << position[0] << ", " << position[1] << ", " << position[2]
      << "), so it has no direction and is skipped; move its focal point.";
  return msg.str();
}
