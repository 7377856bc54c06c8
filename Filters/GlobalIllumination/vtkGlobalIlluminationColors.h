/**
 * @class   vtkGlobalIlluminationColors
 * @brief   how LinkGI reads colour arrays (albedo, emission, irradiance) and the range it
 *          keeps them in: the one rule of the filter and the mapper
 *
 * Reading (Read): a tuple with 1 or 2 components is grey (the first component; a second
 * one is alpha), with 3 or more the first three are RGB (alpha ignored). Unsigned char
 * values are display colours, as colour maps, solid colours and images hold them:
 * divided by 255 and decoded from sRGB to linear RGB (ToLinear), so that light is added
 * and reflected in linear units. Every other type is taken as linear RGB as it is, so
 * float colours may exceed 1 (HDR).
 *
 * Range (Clamp): an albedo is a reflectance in [0, 1]; emission, irradiance and radiance
 * are >= 0 and unbounded. Above 1, an albedo is clamped to 1: that is the filter's
 * ClampAlbedo repair (which warns, or with ClampAlbedo off reports an error). Negative and
 * NaN values are input errors that the filter reports (the solver would spread them); a
 * mapper cannot stop a frame, so Clamp makes them 0, which is what it draws.
 *
 * Part of LinkGI::FiltersGlobalIllumination, used by LinkGI::RenderingGlobalIllumination.
 * Not wrapped.
 */
#ifndef vtkGlobalIlluminationColors_h
#define vtkGlobalIlluminationColors_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro
#include "vtkType.h"                               // for vtkIdType

#include <array> // for std::array

class vtkDataArray;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationColors
{
public:
  using RGB = std::array<double, 3>;

  /// What a colour array holds, which decides its range.
  enum Quantity
  {
    REFLECTANCE = 0, ///< albedo: [0, 1]
    RADIOMETRIC = 1  ///< emission, irradiance, radiance: [0, inf)
  };

  /// Tuple `tuple` of `array` as linear RGB, unclamped (see the class description).
  static RGB Read(vtkDataArray* array, vtkIdType tuple);

  /// A display (sRGB-encoded) value in [0, 1] as linear light: the sRGB decoding curve.
  /// Values outside [0, 1] are clamped first.
  static double ToLinear(double encoded);

  /// Linear light in [0, 1] as a display (sRGB-encoded) value: the inverse of ToLinear.
  static double ToDisplay(double linear);

  /// `rgb` moved into the range of `quantity`, NaN becoming 0 (see the class description).
  static RGB Clamp(const RGB& rgb, Quantity quantity);
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationColors.h
