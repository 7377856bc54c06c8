// vtkGlobalIlluminationRepresentation's properties (forwarded to the filter and the mapper's
// shading) and the counters it reports to ParaView.
#include "vtkGlobalIlluminationRepresentation.h"
#include "vtkGlobalIlluminationRepresentationInternals.h"

#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkPointData.h"

using namespace vtkGlobalIlluminationRepresentationHelpers;

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::SetRaysPerVertex(int rays)
{
  this->Internals->Filter->SetRaysPerVertex(rays);
}

void vtkGlobalIlluminationRepresentation::SetNumberOfBounces(int bounces)
{
  this->Internals->Filter->SetNumberOfBounces(bounces);
}

void vtkGlobalIlluminationRepresentation::SetMethod(int method)
{
  this->Internals->Filter->SetMethod(method);
}

void vtkGlobalIlluminationRepresentation::SetSmoothing(int smoothing)
{
  this->Internals->Filter->SetSmoothing(smoothing);
}

void vtkGlobalIlluminationRepresentation::SetEnvironmentColor(double r, double g, double b)
{
  this->Internals->Filter->SetEnvironmentColor(r, g, b);
}

void vtkGlobalIlluminationRepresentation::SetLightIntensityScale(double scale)
{
  this->Internals->Filter->SetLightIntensityScale(scale);
  Shading(this->Mapper)->SetLightIntensityScale(scale);
}

void vtkGlobalIlluminationRepresentation::SetLightFalloff(int falloff)
{
  // The filter's copies of the lights take it at the next render, as the key light's choice.
  this->LightFalloff = falloff;
  Shading(this->Mapper)->SetLightFalloff(falloff);
}

void vtkGlobalIlluminationRepresentation::SetDisplayMode(int mode)
{
  Shading(this->Mapper)->SetDisplayMode(mode);
}

void vtkGlobalIlluminationRepresentation::SetExposure(double exposure)
{
  Shading(this->Mapper)->SetExposure(exposure);
}

void vtkGlobalIlluminationRepresentation::SetToneMapping(int toneMapping)
{
  Shading(this->Mapper)->SetToneMapping(toneMapping);
}

void vtkGlobalIlluminationRepresentation::SetShadows(int shadows)
{
  Shading(this->Mapper)->SetShadows(shadows);
}

void vtkGlobalIlluminationRepresentation::SetUseKeyLight(bool use)
{
  this->UseKeyLight = use;
}

void vtkGlobalIlluminationRepresentation::SetTemporalBlend(double factor)
{
  this->Internals->Filter->SetTemporalBlend(factor);
}

double vtkGlobalIlluminationRepresentation::GetTemporalBlend()
{
  return this->Internals->Filter->GetTemporalBlend();
}

void vtkGlobalIlluminationRepresentation::SetProgressive(bool progressive)
{
  this->Internals->Filter->SetProgressive(progressive);
}

bool vtkGlobalIlluminationRepresentation::GetProgressive()
{
  return this->Internals->Filter->GetProgressive() != 0;
}

void vtkGlobalIlluminationRepresentation::SetFirstStageSeconds(double seconds)
{
  this->Internals->Filter->SetProgressiveFirstStageSeconds(seconds);
}

void vtkGlobalIlluminationRepresentation::SetMemoryBudget(double mebibytes)
{
  this->Internals->Filter->SetMemoryBudget(mebibytes);
}

void vtkGlobalIlluminationRepresentation::SetProxyVertices(int vertices)
{
  this->Internals->Filter->SetProxyVertices(vertices);
}

double vtkGlobalIlluminationRepresentation::GetFirstStageSeconds()
{
  return this->Internals->Filter->GetProgressiveFirstStageSeconds();
}

//------------------------------------------------------------------------------
double vtkGlobalIlluminationRepresentation::GetPartitionBytesReceived()
{
  return Field(
    this->Internals->Filter->GetOutputDataObject(0), "LinkGI.PartitionBytesReceived");
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetLinkBuilds()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.LinkBuilds");
}

int vtkGlobalIlluminationRepresentation::GetLightLinkBuilds()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.LightLinkBuilds");
}

int vtkGlobalIlluminationRepresentation::GetBounceRuns()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.BounceRuns");
}

int vtkGlobalIlluminationRepresentation::GetNewestRequest()
{
  return static_cast<int>(this->Internals->Filter->GetAsynchronousRequest());
}

int vtkGlobalIlluminationRepresentation::GetShownRequest()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.ShownRequest");
}

int vtkGlobalIlluminationRepresentation::GetShownStage()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.ShownStage");
}

int vtkGlobalIlluminationRepresentation::GetShownStages()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.Stages");
}

int vtkGlobalIlluminationRepresentation::GetSolvingRequest()
{
  return static_cast<int>(this->Internals->Filter->GetAsynchronousSolving());
}

const char* vtkGlobalIlluminationRepresentation::GetLastError()
{
  this->LastError = this->Internals->Filter->GetAsynchronousError();
  return this->LastError.c_str();
}

int vtkGlobalIlluminationRepresentation::GetShadowMapRenders()
{
  return static_cast<vtkGlobalIlluminationCompositeMapper*>(this->Mapper)->GetShadowMapRenderCount();
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetGlobalCasterTriangles()
{
  return static_cast<int>(this->Internals->GlobalCasters->GetNumberOfTriangles());
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetGlobalCasterGathers()
{
  return this->Internals->GlobalCasters->GetNumberOfGathers();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::SetMaximumGlobalCasterTriangles(int triangles)
{
  this->Internals->GlobalCasters->SetMaximumTriangles(triangles);
  this->Modified();
}

int vtkGlobalIlluminationRepresentation::GetNumberOfLights()
{
  return this->Internals->Filter->GetNumberOfLights();
}

double vtkGlobalIlluminationRepresentation::GetMeanIndirectIrradiance()
{
  double sum = 0.0;
  vtkIdType values = 0;
  vtkDataObject* lit = this->Internals->Filter->GetOutputDataObject(0);
  for (vtkDataSet* leaf : vtkCompositeDataSet::GetDataSets<vtkDataSet>(lit))
  {
    vtkDataArray* indirect = leaf->GetPointData()->GetArray("IndirectIrradiance");
    for (vtkIdType i = 0; indirect && i < indirect->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < indirect->GetNumberOfComponents(); ++c)
      {
        sum += indirect->GetComponent(i, c);
      }
    }
    values += indirect ? indirect->GetNumberOfValues() : 0;
  }
  return values > 0 ? sum / values : 0.0;
}

int vtkGlobalIlluminationRepresentation::GetSolvedElements()
{
  return FieldInt(this->Internals->Filter->GetOutputDataObject(0), "LinkGI.Elements");
}

vtkGlobalIlluminationFilter* vtkGlobalIlluminationRepresentation::GetFilter()
{
  return this->Internals->Filter;
}

