#include "vtkGlobalIlluminationShading.h"

#include "vtkDataArray.h"
#include "vtkGlobalIlluminationGlobalCasters.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkGlobalIlluminationShading);

//------------------------------------------------------------------------------
vtkGlobalIlluminationShading::vtkGlobalIlluminationShading()
{
  this->SetAlbedoArrayName("Albedo");
  this->SetIndirectIrradianceArrayName("IndirectIrradiance");
  this->SetEmissionArrayName("Emission");
  this->SetRadianceArrayName("Radiance");
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationShading::~vtkGlobalIlluminationShading()
{
  this->SetAlbedoArrayName(nullptr);
  this->SetIndirectIrradianceArrayName(nullptr);
  this->SetEmissionArrayName(nullptr);
  this->SetRadianceArrayName(nullptr);
  this->SetGlobalCasters(nullptr);
}

//------------------------------------------------------------------------------
vtkCxxSetObjectMacro(vtkGlobalIlluminationShading, GlobalCasters, vtkGlobalIlluminationGlobalCasters);

//------------------------------------------------------------------------------
const char* vtkGlobalIlluminationShading::GetDisplayModeAsString()
{
  switch (this->DisplayMode)
  {
    case DIRECT:
      return "Direct";
    case INDIRECT:
      return "Indirect";
    default:
      return "Combined";
  }
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationShading::Look vtkGlobalIlluminationShading::GetLook(
  bool lamps, const std::vector<vtkDataArray*>& radiance) const
{
  Look look;
  look.Exposure = this->Exposure;
  if (this->ToneMapping != AUTOMATIC)
  {
    look.ToneMapping = this->ToneMapping;
  }
  else if (lamps)
  {
    // A lamp's 1/r^2 range needs compressing: a photograph, exposed for the scene.
    look.ToneMapping = EXPONENTIAL;
    look.Exposure *= this->SuggestExposure(radiance, EXPONENTIAL);
  }
  else
  {
    look.ToneMapping = HUE_PRESERVING; // calibrated to VTK's Surface
  }
  return look;
}

//------------------------------------------------------------------------------
double vtkGlobalIlluminationShading::SuggestExposure(vtkDataArray* radiance) const
{
  const int curve = this->ToneMapping == AUTOMATIC ? EXPONENTIAL : this->ToneMapping;
  return this->SuggestExposure(std::vector<vtkDataArray*>{ radiance }, curve);
}

//------------------------------------------------------------------------------
double vtkGlobalIlluminationShading::SuggestExposure(
  const std::vector<vtkDataArray*>& radiance, int toneMapping) const
{
  std::vector<double> luminance;
  for (vtkDataArray* array : radiance)
  {
    if (!array || array->GetNumberOfComponents() < 3)
    {
      continue;
    }
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      const double* c = array->GetTuple3(i);
      luminance.push_back(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]);
    }
  }
  const std::size_t n = luminance.size();
  if (n == 0)
  {
    return 1.0;
  }
  // The curves compress highlights, so the 95th percentile can go near white; the
  // hue-preserving display is linear up to white, so a lower one does (the brightest
  // fifth, around lamps, turns white as in a photograph).
  const std::size_t rank = toneMapping == HUE_PRESERVING ? n * 80 / 100 : n * 95 / 100;
  const auto percentile = luminance.begin() + static_cast<std::ptrdiff_t>(rank);
  std::nth_element(luminance.begin(), percentile, luminance.end());
  if (!(*percentile > 0.0) || !std::isfinite(*percentile))
  {
    return 1.0;
  }
  const double target = 0.85;
  switch (toneMapping)
  {
    case EXPONENTIAL: // 1 - exp(-x), then the gamma encoding
      return -std::log(1.0 - std::pow(target, this->Gamma)) / *percentile;
    case REINHARD: // x / (1 + x)
    {
      const double y = std::pow(target, this->Gamma);
      return y / (1.0 - y) / *percentile;
    }
    case LINEAR:
      return std::pow(target, this->Gamma) / *percentile;
    default: // display = Exposure * colour * irradiance, and pi L = albedo * irradiance
      return target / (vtkMath::Pi() * *percentile);
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationShading::PrintSelf(ostream& os, vtkIndent indent)
{
  const auto name = [](const char* s) { return s ? s : "(none)"; };
  static const char* const curves[] = { "Linear", "Exponential", "Reinhard", "Hue Preserving",
    "Automatic" };
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Display Mode: " << this->GetDisplayModeAsString() << "\n";
  os << indent << "Albedo Array Name: " << name(this->AlbedoArrayName) << "\n";
  os << indent << "Indirect Irradiance Array Name: " << name(this->IndirectIrradianceArrayName)
     << "\n";
  os << indent << "Emission Array Name: " << name(this->EmissionArrayName) << "\n";
  os << indent << "Radiance Array Name: " << name(this->RadianceArrayName) << "\n";
  os << indent << "Light Intensity Scale: " << this->LightIntensityScale << "\n";
  os << indent << "Light Falloff: " << (this->LightFalloff ? "Inverse Square" : "As Light")
     << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "Tone Mapping: " << curves[this->ToneMapping] << "\n";
  os << indent << "Gamma: " << this->Gamma << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "On" : "Off") << "\n";
  os << indent << "Shadow Map Resolution: " << this->ShadowMapResolution << "\n";
  os << indent << "Shadow Filter Radius: " << this->ShadowFilterRadius << "\n";
  os << indent << "Shadow Bias: " << this->ShadowBias << "\n";
  os << indent << "Global Casters: " << this->GlobalCasters << "\n";
}
