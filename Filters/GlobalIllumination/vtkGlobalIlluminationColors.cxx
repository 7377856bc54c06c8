#include "vtkGlobalIlluminationColors.h"

#include "vtkDataArray.h"

//------------------------------------------------------------------------------
vtkGlobalIlluminationColors::RGB vtkGlobalIlluminationColors::Read(
  vtkDataArray* array, vtkIdType tuple)
{
  const double scale = array->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  const bool grey = array->GetNumberOfComponents() < 3;
  RGB rgb;
  for (int k = 0; k < 3; ++k)
  {
    rgb[k] = array->GetComponent(tuple, grey ? 0 : k) * scale;
  }
  return rgb;
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationColors::RGB vtkGlobalIlluminationColors::Clamp(
  const RGB& rgb, Quantity quantity)
{
  RGB out;
  for (int k = 0; k < 3; ++k)
  {
    // Written so that NaN fails the comparison and becomes 0.
    const double v = rgb[k] > 0.0 ? rgb[k] : 0.0;
    out[k] = (quantity == REFLECTANCE && v > 1.0) ? 1.0 : v;
  }
  return out;
}
