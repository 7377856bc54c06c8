#include "vtkGlobalIlluminationDrawnColors.h"

#include "vtkCellData.h"
#include "vtkDataSet.h"
#include "vtkMapper.h"
#include "vtkPointData.h"
#include "vtkScalarsToColors.h"

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationDrawnColors::MapsScalars(vtkMapper* mapper, bool& cells)
{
  const char* name = mapper ? mapper->GetArrayName() : nullptr;
  cells = mapper && mapper->GetScalarMode() == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA;
  return mapper && mapper->GetScalarVisibility() && name && *name && mapper->GetLookupTable() &&
    mapper->GetScalarMode() != VTK_SCALAR_MODE_USE_FIELD_DATA;
}

//------------------------------------------------------------------------------
vtkDataArray* vtkGlobalIlluminationDrawnColors::ColoringArray(
  vtkDataSet* data, vtkMapper* mapper, bool cells)
{
  vtkDataSetAttributes* attributes = cells
    ? static_cast<vtkDataSetAttributes*>(data->GetCellData())
    : static_cast<vtkDataSetAttributes*>(data->GetPointData());
  return attributes->GetArray(mapper->GetArrayName());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkUnsignedCharArray> vtkGlobalIlluminationDrawnColors::Map(
  vtkMapper* mapper, vtkDataArray* scalars)
{
  return vtk::TakeSmartPointer(mapper->GetLookupTable()->MapScalars(
    scalars, mapper->GetColorMode(), mapper->GetArrayComponent(), VTK_RGBA));
}
