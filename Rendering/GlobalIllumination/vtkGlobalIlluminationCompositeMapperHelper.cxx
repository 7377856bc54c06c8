#include "vtkGlobalIlluminationCompositeMapperHelper.h"

#include "vtkGlobalIlluminationMapperCore.h"

#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkGlobalIlluminationCompositeMapperHelper);

//------------------------------------------------------------------------------
vtkGlobalIlluminationCompositeMapperHelper::vtkGlobalIlluminationCompositeMapperHelper()
  : Core(new vtkGlobalIlluminationMapperCore(this))
{
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationCompositeMapperHelper::~vtkGlobalIlluminationCompositeMapperHelper() = default;

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::SetShading(vtkGlobalIlluminationShading* shading)
{
  this->Core->SetShading(shading);
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationCompositeMapperHelper::GetShadowMapRenderCount()
{
  return this->Core->GetShadowMapRenderCount();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Core->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationCompositeMapperHelper::Shades(
  const vtkOpenGLHelper* cellBO, vtkActor* act)
{
  const std::ptrdiff_t type = cellBO - this->Primitives;
  if (type < PrimitiveStart || type >= PrimitiveEnd)
  {
    return false;
  }
  return vtkGlobalIlluminationMapperCore::Shades(
    static_cast<int>(type), this->PrimitiveInfo[cellBO].LastLightComplexity, act);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  if (!ren->GetSelector())
  {
    // Blocks are appended into one position buffer at every build, so the build time is
    // as fine a version as any here.
    this->Core->Prepare(ren, act,
      vtkGlobalIlluminationMapperCore::MakeCasters(
        this->VBOs, this->Primitives, act, this->VBOBuildTime.GetMTime()));
  }
  this->Superclass::RenderPieceDraw(ren, act);
  this->Core->FinishDraw();
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationCompositeMapperHelper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  bool rebuild = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act);
  const std::string key = this->Shades(&cellBO, act) ? this->Core->ShaderKey(act) : "VTK";
  std::string& last = this->ShaderKeys[&cellBO];
  if (key != last)
  {
    last = key;
    rebuild = true;
  }
  return rebuild;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::ReplaceShaderLight(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  if (this->Shades(this->LastBoundBO, act))
  {
    this->Core->ReplaceShaderLight(shaders, act);
  }
  else
  {
    this->Superclass::ReplaceShaderLight(shaders, ren, act);
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::SetLightingShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  if (this->Shades(&cellBO, act))
  {
    this->Core->SetShaderParameters(cellBO.Program, ren);
  }
  else
  {
    this->Superclass::SetLightingShaderParameters(cellBO, ren, act);
  }
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationCompositeMapperHelper::GetNeedToRebuildBufferObjects(
  vtkRenderer* ren, vtkActor* act)
{
  const bool rebuild = this->Superclass::GetNeedToRebuildBufferObjects(ren, act);
  return rebuild || this->Core->BufferKey() != this->BufferKey;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  // An attribute is in the buffer if any block has it; AppendOneBufferObject fills the
  // blocks that lack it.
  vtkGlobalIlluminationMapperCore::Layout layout;
  for (const auto& entry : this->Data)
  {
    const vtkGlobalIlluminationMapperCore::Layout block = this->Core->GetLayout(entry.first);
    layout.Albedo = layout.Albedo || block.Albedo;
    layout.Indirect = layout.Indirect || block.Indirect;
    layout.IndirectBack = layout.IndirectBack || block.IndirectBack;
    layout.Emission = layout.Emission || block.Emission;
  }
  this->Core->SetLayout(layout);
  this->Core->ClearKept();
  this->Superclass::BuildBufferObjects(ren, act);
  this->Core->ClearKept();
  this->BufferKey = this->Core->BufferKey();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::AppendOneBufferObject(vtkRenderer* ren,
  vtkActor* act, vtkCompositeMapperHelperData* hdata, vtkIdType& flatIndex,
  std::vector<unsigned char>& colors, std::vector<float>& norms)
{
  // Blocks that share their points with an earlier block share its vertices in the buffer
  // (vtkOpenGLVertexBufferObjectGroup appends an array once), and so its attributes.
  vtkIdType offset = 0, total = 0;
  vtkPoints* points = hdata->Data->GetPoints();
  const bool shared =
    points && this->VBOs->ArrayExists("vertexMC", points->GetData(), offset, total);
  this->Superclass::AppendOneBufferObject(ren, act, hdata, flatIndex, colors, norms);
  if (shared)
  {
    return;
  }
  const auto attributes = this->Core->MakeAttributes(hdata->Data, true);
  this->Core->Keep(attributes);
  const vtkGlobalIlluminationMapperCore::Layout& layout = this->Core->GetLayout();
  if (layout.Albedo)
  {
    this->VBOs->AppendDataArray("giAlbedoMC", attributes.Albedo, VTK_FLOAT);
  }
  if (layout.Indirect)
  {
    this->VBOs->AppendDataArray("giIndirectMC", attributes.Indirect, VTK_FLOAT);
  }
  if (layout.IndirectBack)
  {
    this->VBOs->AppendDataArray("giIndirectBackMC", attributes.IndirectBack, VTK_FLOAT);
  }
  if (layout.Emission)
  {
    this->VBOs->AppendDataArray("giEmissionMC", attributes.Emission, VTK_FLOAT);
  }
}
