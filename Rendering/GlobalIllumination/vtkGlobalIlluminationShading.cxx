#include "vtkGlobalIlluminationShading.h"

#include "vtkObjectFactory.h"

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
}

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
void vtkGlobalIlluminationShading::PrintSelf(ostream& os, vtkIndent indent)
{
  const auto name = [](const char* s) { return s ? s : "(none)"; };
  static const char* const curves[] = { "Linear", "Exponential", "Reinhard" };
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
}
