#include "vtkGlobalIlluminationRepresentation.h"

#include "vtkGlobalIlluminationBlockMerger.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationCompositeMapper.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationShading.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPVLight.h"
#include "vtkPVRenderView.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVariant.h"

#include <set>
#include <string>
#include <vector>

namespace
{
/// `point` (x, y, z) moved by the homogeneous `matrix`.
void Transform(vtkMatrix4x4* matrix, double point[3])
{
  double in[4] = { point[0], point[1], point[2], 1.0 }, out[4];
  matrix->MultiplyPoint(in, out);
  for (int i = 0; i < 3; ++i)
  {
    point[i] = out[3] != 0.0 ? out[i] / out[3] : out[i];
  }
}

vtkGlobalIlluminationShading* Shading(vtkMapper* mapper)
{
  return static_cast<vtkGlobalIlluminationCompositeMapper*>(mapper)->GetShading();
}

int FieldInt(vtkPolyData* data, const char* name)
{
  vtkAbstractArray* array = data ? data->GetFieldData()->GetAbstractArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetVariantValue(0).ToInt() : 0;
}
}

//------------------------------------------------------------------------------
struct vtkGlobalIlluminationRepresentation::vtkInternals
{
  vtkNew<vtkGlobalIlluminationFilter> Filter;
  vtkGlobalIlluminationBlockMerger Merger;
  std::vector<vtkSmartPointer<vtkLight>> Lights; // world-space copies of the view's lights
  bool Executed = false;                         // the filter ran since the last scatter
  std::set<std::string> Warnings;                // each shown once
};

vtkStandardNewMacro(vtkGlobalIlluminationRepresentation);

//------------------------------------------------------------------------------
vtkGlobalIlluminationRepresentation::vtkGlobalIlluminationRepresentation()
  : Internals(new vtkInternals)
{
  // Replace the superclass's mapper, keeping what it set up for selection.
  this->Mapper->Delete();
  vtkGlobalIlluminationCompositeMapper* mapper = vtkGlobalIlluminationCompositeMapper::New();
  mapper->SetProcessIdArrayName("vtkProcessId");
  mapper->SetCompositeIdArrayName("vtkCompositeIndex");
  this->Mapper = mapper;
  this->SetArrayIdNames(nullptr, nullptr);
  this->SuppressLOD = true;
  this->SetupDefaults();

  vtkGlobalIlluminationFilter* filter = this->Internals->Filter;
  filter->AddObserver(vtkCommand::ProgressEvent, this, &vtkGlobalIlluminationRepresentation::OnFilterEvent);
  filter->AddObserver(vtkCommand::EndEvent, this, &vtkGlobalIlluminationRepresentation::OnFilterEvent);
  filter->AddObserver(vtkCommand::WarningEvent, this, &vtkGlobalIlluminationRepresentation::OnFilterEvent);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::OnFilterEvent(vtkObject*, unsigned long event, void* data)
{
  vtkInternals& internals = *this->Internals;
  if (event == vtkCommand::ProgressEvent)
  {
    // Through this representation, ParaView's progress bar shows the filter's progress.
    this->SetProgressText(internals.Filter->GetProgressText());
    this->UpdateProgress(internals.Filter->GetProgress());
  }
  else if (event == vtkCommand::EndEvent)
  {
    internals.Executed = true;
    ++this->NumberOfUpdates;
  }
  else if (event == vtkCommand::WarningEvent && data)
  {
    // The filter runs on every light change: show each of its warnings once, not per frame.
    const std::string message = static_cast<const char*>(data);
    if (internals.Warnings.insert(message).second)
    {
      vtkWarningMacro(<< message);
    }
  }
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationRepresentation::~vtkGlobalIlluminationRepresentation() = default;

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::SetSuppressLOD(bool)
{
  this->SuppressLOD = true;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  auto cmapper = vtkCompositePolyDataMapper2::SafeDownCast(this->Mapper);
  vtkCompositeDataDisplayAttributes* attributes =
    cmapper ? cmapper->GetCompositeDataDisplayAttributes() : nullptr;
  const vtkMTimeType attributesTime = attributes ? attributes->GetMTime() : 0;

  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  vtkPVRenderView* view = vtkPVRenderView::SafeDownCast(this->GetView());
  if (request_type != vtkPVView::REQUEST_RENDER() || !view)
  {
    return 1;
  }

  // The superclass gave the mapper the delivered data; draw the lit copy instead, with the
  // block attributes (colours, visibilities) moved onto the copy's blocks.
  vtkDataObject* delivered = vtkPVView::GetDeliveredPiece(inInfo, this);
  vtkDataObject* before = this->Internals->Merger.GetOutput();
  this->UpdateGlobalIllumination(delivered, view->GetRenderer());
  vtkDataObject* lit = this->Internals->Merger.GetOutput();
  this->Mapper->SetInputDataObject(lit);
  if (attributes && lit && (lit != before || attributes->GetMTime() != attributesTime))
  {
    this->PopulateBlockAttributes(attributes, lit);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::UpdateGlobalIllumination(
  vtkDataObject* delivered, vtkRenderer* renderer)
{
  vtkInternals& internals = *this->Internals;
  vtkGlobalIlluminationFilter* filter = internals.Filter;

  // The albedo is what the mapper draws: coloring array through the lookup table, or the
  // solid colour (UpdateColoringParameters already ran in the superclass's request).
  vtkGlobalIlluminationBlockMerger::Albedo albedo;
  const char* colorArray = this->Mapper->GetArrayName();
  albedo.MapScalars = this->Mapper->GetScalarVisibility() && colorArray && *colorArray &&
    this->Mapper->GetLookupTable() &&
    this->Mapper->GetScalarMode() != VTK_SCALAR_MODE_USE_FIELD_DATA;
  if (albedo.MapScalars)
  {
    albedo.ArrayName = colorArray;
    albedo.Association = this->Mapper->GetScalarMode() == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA ? 1 : 0;
    albedo.LookupTable = this->Mapper->GetLookupTable();
    albedo.ColorMode = this->Mapper->GetColorMode();
    albedo.Component = this->Mapper->GetArrayComponent();
  }
  this->Property->GetDiffuseColor(albedo.Color);
  albedo.Diffuse = this->Property->GetDiffuse();

  vtkGlobalIlluminationBlockMerger& merger = internals.Merger;
  const bool merged = merger.Merge(delivered, albedo);
  filter->SetAlbedoArrayName(merger.HasAlbedoArray() ? merger.AlbedoArrayName() : nullptr);
  filter->SetAlbedoArrayAssociation(merger.HasAlbedoArray() ? merger.GetAlbedoAssociation() : 0);
  filter->SetAlbedo(albedo.Color[0] * albedo.Diffuse, albedo.Color[1] * albedo.Diffuse,
    albedo.Color[2] * albedo.Diffuse);
  filter->SetEmissionArrayName(merger.HasEmission() ? "Emission" : nullptr);
  this->GatherLights(renderer);

  double sky[3];
  filter->GetEnvironmentColor(sky);
  const bool dark = filter->GetNumberOfLights() == 0 && !merger.HasEmission() &&
    sky[0] <= 0.0 && sky[1] <= 0.0 && sky[2] <= 0.0;
  static const std::vector<std::string> arrays = { "DirectIrradiance", "IndirectIrradiance",
    "Radiance" };
  if (merger.GetNumberOfPoints() == 0 || dark)
  {
    // Nothing to solve: no indirect light (the mapper draws the direct light, if any).
    merger.Scatter(nullptr, arrays);
    return;
  }
  if (filter->GetInput() != merger.GetMerged())
  {
    filter->SetInputData(merger.GetMerged());
  }
  filter->Update();
  if (merged || internals.Executed)
  {
    merger.Scatter(filter->GetOutput(), arrays);
    internals.Executed = false;
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::GatherLights(vtkRenderer* renderer)
{
  vtkInternals& internals = *this->Internals;
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkMatrix4x4* cameraToWorld = camera->GetCameraLightTransformMatrix();

  std::size_t count = 0;
  bool keyLightTaken = false;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    const bool inspectorLight = vtkPVLight::SafeDownCast(light) != nullptr;
    if (!light->GetSwitch() || light->GetLightType() == VTK_LIGHT_TYPE_AMBIENT_LIGHT)
    {
      continue;
    }
    if (!inspectorLight)
    {
      // The light kit adds its head light, then its key light, then fill and back lights;
      // its key light is the first of its camera lights.
      if (!this->UseKeyLight || keyLightTaken || !light->LightTypeIsCameraLight())
      {
        continue;
      }
      keyLightTaken = true;
    }
    double position[3], focalPoint[3];
    light->GetPosition(position);
    light->GetFocalPoint(focalPoint);
    if (light->LightTypeIsHeadlight())
    {
      camera->GetPosition(position);
      camera->GetFocalPoint(focalPoint);
    }
    else if (light->LightTypeIsCameraLight())
    {
      // Where the renderer will place it for this frame's camera.
      Transform(cameraToWorld, position);
      Transform(cameraToWorld, focalPoint);
    }
    if (count == internals.Lights.size())
    {
      internals.Lights.push_back(vtkSmartPointer<vtkLight>::New());
    }
    // vtkLight's setters change nothing (and so trigger no update) when values are equal.
    vtkLight* copy = internals.Lights[count++];
    copy->SetLightTypeToSceneLight();
    copy->SetPositional(light->GetPositional());
    copy->SetPosition(position);
    copy->SetFocalPoint(focalPoint);
    copy->SetConeAngle(light->GetConeAngle());
    copy->SetExponent(light->GetExponent());
    copy->SetDiffuseColor(light->GetDiffuseColor());
    copy->SetIntensity(light->GetIntensity());
  }
  vtkGlobalIlluminationFilter* filter = internals.Filter;
  if (static_cast<int>(count) != filter->GetNumberOfLights())
  {
    filter->RemoveAllLights();
    for (std::size_t i = 0; i < count; ++i)
    {
      filter->AddLight(internals.Lights[i]);
    }
  }
}

//------------------------------------------------------------------------------

void vtkGlobalIlluminationRepresentation::SetRaysPerVertex(int rays)
{
  this->Internals->Filter->SetRaysPerVertex(rays);
}

void vtkGlobalIlluminationRepresentation::SetNumberOfBounces(int bounces)
{
  this->Internals->Filter->SetNumberOfBounces(bounces);
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

void vtkGlobalIlluminationRepresentation::SetDisplayMode(int mode)
{
  Shading(this->Mapper)->SetDisplayMode(mode);
}

void vtkGlobalIlluminationRepresentation::SetExposure(double exposure)
{
  Shading(this->Mapper)->SetExposure(exposure);
}

void vtkGlobalIlluminationRepresentation::SetShadows(int shadows)
{
  Shading(this->Mapper)->SetShadows(shadows);
}

void vtkGlobalIlluminationRepresentation::SetUseKeyLight(bool use)
{
  this->UseKeyLight = use;
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationRepresentation::GetLinkBuilds()
{
  return FieldInt(this->Internals->Filter->GetOutput(), "LinkGI.LinkBuilds");
}

int vtkGlobalIlluminationRepresentation::GetLightLinkBuilds()
{
  return FieldInt(this->Internals->Filter->GetOutput(), "LinkGI.LightLinkBuilds");
}

int vtkGlobalIlluminationRepresentation::GetBounceRuns()
{
  return FieldInt(this->Internals->Filter->GetOutput(), "LinkGI.BounceRuns");
}

int vtkGlobalIlluminationRepresentation::GetNumberOfLights()
{
  return this->Internals->Filter->GetNumberOfLights();
}

double vtkGlobalIlluminationRepresentation::GetMeanIndirectIrradiance()
{
  vtkPolyData* output = this->Internals->Filter->GetOutput();
  vtkDataArray* indirect = output->GetPointData()->GetArray("IndirectIrradiance");
  if (!indirect || indirect->GetNumberOfTuples() == 0)
  {
    return 0.0;
  }
  double sum = 0.0;
  for (vtkIdType i = 0; i < indirect->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < indirect->GetNumberOfComponents(); ++c)
    {
      sum += indirect->GetComponent(i, c);
    }
  }
  return sum / (indirect->GetNumberOfTuples() * indirect->GetNumberOfComponents());
}

vtkGlobalIlluminationFilter* vtkGlobalIlluminationRepresentation::GetFilter()
{
  return this->Internals->Filter;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Use Key Light: " << (this->UseKeyLight ? "On" : "Off") << "\n";
  os << indent << "Number Of Updates: " << this->NumberOfUpdates << "\n";
  os << indent << "Filter:\n";
  this->Internals->Filter->PrintSelf(os, indent.GetNextIndent());
}
