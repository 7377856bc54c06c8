#include "vtkGlobalIlluminationMapper.h"

#include "vtkGlobalIlluminationMapperCore.h"
#include "vtkGlobalIlluminationShading.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"

#include <algorithm>

vtkStandardNewMacro(vtkGlobalIlluminationMapper);

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapper::vtkGlobalIlluminationMapper()
  : Core(new vtkGlobalIlluminationMapperCore(this))
{
  this->SetShading(nullptr);
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationMapper::~vtkGlobalIlluminationMapper()
{
  if (this->Shading)
  {
    this->Shading->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapper::SetShading(vtkGlobalIlluminationShading* shading)
{
  if (shading && shading == this->Shading)
  {
    return;
  }
  if (this->Shading)
  {
    this->Shading->Delete();
  }
  this->Shading = shading ? shading : vtkGlobalIlluminationShading::New();
  if (shading)
  {
    shading->Register(this);
  }
  this->Core->SetShading(this->Shading);
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationMapper::GetShadowMapRenderCount()
{
  return this->Core->GetShadowMapRenderCount();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Core->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
  this->GeometryKey.clear(); // the buffers are gone: the next build is a full one
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationMapper::Shades(const vtkOpenGLHelper* cellBO, vtkActor* act)
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
void vtkGlobalIlluminationMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  if (!ren->GetSelector())
  {
    const std::vector<vtkPolyData*> drawn{ this->CurrentInput };
    this->Core->Prepare(ren, act,
      vtkGlobalIlluminationMapperCore::MakeCasters(this->VBOs, this->Primitives, act, drawn), drawn);
  }
  this->Superclass::RenderPieceDraw(ren, act);
  this->Core->FinishDraw();
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationMapper::GetNeedToRebuildShaders(
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
void vtkGlobalIlluminationMapper::ReplaceShaderLight(
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
void vtkGlobalIlluminationMapper::SetLightingShaderParameters(
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
bool vtkGlobalIlluminationMapper::GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act)
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
  // Only the light arrays changed (vtkGlobalIlluminationMapperCore::GeometryKey): upload
  // the shading attributes alone, if they have the built layout.
  const std::vector<vtkPolyData*> input{ this->CurrentInput };
  if (ren->GetSelector() || this->GeometryKey.empty() ||
    !(this->Core->GetLayout(this->CurrentInput) == this->Core->GetLayout()) ||
    this->Core->GeometryKey(this, act, input) != this->GeometryKey)
  {
    return true;
  }
  const std::string shading = this->Core->ShadingKey(input);
  if (shading != this->ShadingKey)
  {
    this->Core->UploadShading(this->VBOs, input, false);
    this->ShadingKey = shading;
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  // The shading attributes get VBOs of their own next to VTK's; the superclass builds them
  // all together.
  const auto attributes = this->Core->MakeAttributes(this->CurrentInput, false);
  this->Core->ClearKept();
  this->Core->Keep(attributes);
  auto* cache = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())->GetVBOCache();
  vtkGlobalIlluminationMapperCore::Layout layout;
  for (const auto& buffer : vtkGlobalIlluminationMapperCore::Buffers())
  {
    this->VBOs->CacheDataArray(buffer.Name, attributes.*buffer.Array, cache, VTK_FLOAT);
    layout.*buffer.Present = attributes.*buffer.Array != nullptr;
  }
  this->Superclass::BuildBufferObjects(ren, act);
  this->Core->SetLayout(layout);
  this->BufferKey = this->Core->BufferKey();
  const std::vector<vtkPolyData*> input{ this->CurrentInput };
  // Buffers built during a selection pass are not kept (a selector may change what the
  // superclass builds): the next normal render builds them in full.
  this->GeometryKey = ren->GetSelector() ? std::string() : this->Core->GeometryKey(this, act, input);
  this->ShadingKey = this->Core->ShadingKey(input);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shading: " << this->Shading << "\n";
  if (this->Shading)
  {
    this->Shading->PrintSelf(os, indent.GetNextIndent());
  }
  os << indent << "Shadow Map Render Count: " << this->Core->GetShadowMapRenderCount() << "\n";
}
