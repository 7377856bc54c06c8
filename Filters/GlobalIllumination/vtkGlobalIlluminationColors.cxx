#include "vtkGlobalIlluminationColors.h"

#include "vtkDataArray.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
vtkGlobalIlluminationColors::RGB vtkGlobalIlluminationColors::Read(
  vtkDataArray* array, vtkIdType tuple)
{
  const bool display = array->GetDataType() == VTK_UNSIGNED_CHAR;
  const bool grey = array->GetNumberOfComponents() < 3;
  RGB rgb;
  for (int k = 0; k < 3; ++k)
  {
    const double v = array->GetComponent(tuple, grey ? 0 : k);
    rgb[k] = display ? ToLinear(v / 255.0) : v;
  }
  return rgb;
}

//------------------------------------------------------------------------------
double vtkGlobalIlluminationColors::ToLinear(double encoded)
{
  // Written so that NaN fails the comparison and becomes 0.
  const double c = encoded > 0.0 ? std::min(encoded, 1.0) : 0.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

//------------------------------------------------------------------------------
double vtkGlobalIlluminationColors::ToDisplay(double linear)
{
  const double c = linear > 0.0 ? std::min(linear, 1.0) : 0.0;
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
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
