#include "vtkGlobalIlluminationCompositeMapperHelper.h"

#include "vtkGlobalIlluminationMapperCore.h"

#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkGlobalIlluminationCompositeMapperHelper);

namespace
{
/// The shading attributes any block has: the vertex buffers' layout. AppendOneBufferObject
/// fills the blocks that lack one.
vtkGlobalIlluminationMapperCore::Layout BlocksLayout(const vtkGlobalIlluminationMapperCore& core,
  const std::map<vtkPolyData*, vtkCompositeMapperHelperData*>& blocks)
{
  vtkGlobalIlluminationMapperCore::Layout layout;
  for (const auto& entry : blocks)
  {
    const vtkGlobalIlluminationMapperCore::Layout block = core.GetLayout(entry.first);
    for (const auto& buffer : vtkGlobalIlluminationMapperCore::Buffers())
    {
      layout.*buffer.Present = layout.*buffer.Present || block.*buffer.Present;
    }
  }
  return layout;
}
}

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
  this->GeometryKey.clear(); // the buffers are gone: the next build is a full one
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
    this->Core->Prepare(ren, act,
      vtkGlobalIlluminationMapperCore::MakeCasters(this->VBOs, this->Primitives, act, this->ShadedBlocks),
      this->ShadedBlocks);
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
  // The superclass is asked first, always: it records what it has seen.
  const bool rebuild = this->Superclass::GetNeedToRebuildBufferObjects(ren, act);
  if (this->Core->BufferKey() != this->BufferKey)
  {
    return true;
  }
  if (!rebuild)
  {
    return false;
  }
  if (ren->GetSelector() || this->GeometryKey.empty() ||
    !(BlocksLayout(*this->Core, this->Data) == this->Core->GetLayout()) ||
    this->MakeGeometryKey(act) != this->GeometryKey)
  {
    return true;
  }
  const std::string shading = this->Core->ShadingKey(this->ShadedBlocks);
  if (shading != this->ShadingKey)
  {
    this->Core->UploadShading(this->VBOs, this->ShadedBlocks, true);
    this->ShadingKey = shading;
  }
  return false;
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationCompositeMapperHelper::MakeGeometryKey(vtkActor* act)
{
  std::vector<vtkPolyData*> blocks;
  for (const auto& entry : this->Data)
  {
    blocks.push_back(entry.first);
  }
  return this->Core->GeometryKey(this, act, blocks);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapperHelper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  this->Core->SetLayout(BlocksLayout(*this->Core, this->Data));
  this->Core->ClearKept();
  this->ShadedBlocks.clear();
  this->Superclass::BuildBufferObjects(ren, act);
  this->Core->ClearKept();
  this->BufferKey = this->Core->BufferKey();
  // Buffers built during a selection pass are not kept (a selector may change what the
  // superclass builds): the next normal render builds them in full.
  this->GeometryKey = ren->GetSelector() ? std::string() : this->MakeGeometryKey(act);
  this->ShadingKey = this->Core->ShadingKey(this->ShadedBlocks);
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
  this->ShadedBlocks.push_back(hdata->Data);
  const auto attributes = this->Core->MakeAttributes(hdata->Data, true);
  this->Core->Keep(attributes);
  const vtkGlobalIlluminationMapperCore::Layout& layout = this->Core->GetLayout();
  for (const auto& buffer : vtkGlobalIlluminationMapperCore::Buffers())
  {
    if (layout.*buffer.Present)
    {
      this->VBOs->AppendDataArray(buffer.Name, attributes.*buffer.Array, VTK_FLOAT);
    }
  }
}
