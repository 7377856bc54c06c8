#include "vtkGlobalIlluminationCompositeMapper.h"

#include "vtkGlobalIlluminationCompositeMapperHelper.h"
#include "vtkGlobalIlluminationShading.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkGlobalIlluminationCompositeMapper);

//------------------------------------------------------------------------------
vtkGlobalIlluminationCompositeMapper::vtkGlobalIlluminationCompositeMapper()
{
  this->SetShading(nullptr);
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationCompositeMapper::~vtkGlobalIlluminationCompositeMapper()
{
  if (this->Shading)
  {
    this->Shading->Delete();
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapper::SetShading(vtkGlobalIlluminationShading* shading)
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
  for (auto& helper : this->Helpers)
  {
    static_cast<vtkGlobalIlluminationCompositeMapperHelper*>(helper.second)
      ->SetShading(this->Shading);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkGlobalIlluminationCompositeMapper::GetShadowMapRenderCount()
{
  int count = 0;
  for (auto& helper : this->Helpers)
  {
    count += static_cast<vtkGlobalIlluminationCompositeMapperHelper*>(helper.second)
               ->GetShadowMapRenderCount();
  }
  return count;
}

//------------------------------------------------------------------------------
vtkCompositeMapperHelper2* vtkGlobalIlluminationCompositeMapper::CreateHelper()
{
  return vtkGlobalIlluminationCompositeMapperHelper::New();
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapper::CopyMapperValuesToHelper(
  vtkCompositeMapperHelper2* helper)
{
  this->Superclass::CopyMapperValuesToHelper(helper);
  static_cast<vtkGlobalIlluminationCompositeMapperHelper*>(helper)->SetShading(this->Shading);
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationCompositeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shading: " << this->Shading << "\n";
  if (this->Shading)
  {
    this->Shading->PrintSelf(os, indent.GetNextIndent());
  }
}
