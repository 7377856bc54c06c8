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
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationShading::~vtkGlobalIlluminationShading()
{
  this->SetAlbedoArrayName(nullptr);
  this->SetIndirectIrradianceArrayName(nullptr);
  this->SetEmissionArrayName(nullptr);
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
double vtkGlobalIlluminationShading::SuggestExposure(vtkDataArray* radiance) const
{
  const vtkIdType n =
    radiance && radiance->GetNumberOfComponents() >= 3 ? radiance->GetNumberOfTuples() : 0;
  if (n == 0)
  {
    return 1.0;
  }
  std::vector<double> luminance(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double* c = radiance->GetTuple3(i);
    luminance[i] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  }
  // The curves compress highlights, so the 95th percentile can go near white; the
  // hue-preserving display is linear up to white, so a lower one does (the brightest
  // fifth, around lamps, turns white as in a photograph).
  const vtkIdType rank = this->ToneMapping == HUE_PRESERVING ? n * 80 / 100 : n * 95 / 100;
  const auto percentile = luminance.begin() + rank;
  std::nth_element(luminance.begin(), percentile, luminance.end());
  if (!(*percentile > 0.0))
  {
    return 1.0;
  }
  const double target = 0.85;
  switch (this->ToneMapping)
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
  static const char* const curves[] = { "Linear", "Exponential", "Reinhard", "Hue Preserving" };
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Display Mode: " << this->GetDisplayModeAsString() << "\n";
  os << indent << "Albedo Array Name: " << name(this->AlbedoArrayName) << "\n";
  os << indent << "Indirect Irradiance Array Name: " << name(this->IndirectIrradianceArrayName)
     << "\n";
  os << indent << "Emission Array Name: " << name(this->EmissionArrayName) << "\n";
  os << indent << "Light Intensity Scale: " << this->LightIntensityScale << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "Tone Mapping: " << curves[this->ToneMapping] << "\n";
  os << indent << "Gamma: " << this->Gamma << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "On" : "Off") << "\n";
  os << indent << "Shadow Map Resolution: " << this->ShadowMapResolution << "\n";
  os << indent << "Shadow Filter Radius: " << this->ShadowFilterRadius << "\n";
  os << indent << "Shadow Bias: " << this->ShadowBias << "\n";
  os << indent << "Global Casters: " << this->GlobalCasters << "\n";
}
