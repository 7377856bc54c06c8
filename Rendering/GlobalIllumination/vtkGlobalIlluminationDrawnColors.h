/**
 * The colour a mapper draws a dataset with, before lighting: the one rule that
 * vtkGlobalIlluminationDrawnAlbedo (the filter's albedo) and
 * vtkGlobalIlluminationDisplayColors (the displayed colours, baked) share.
 *
 * With scalar visibility on, a named colouring array, a lookup table and a point or cell
 * scalar mode, the mapper maps that array through its lookup table (colour mode and
 * component as it uses them); otherwise it draws the property's solid colour. Both are
 * display (sRGB) values, times the property's Diffuse in the shaders.
 *
 * Not wrapped, not installed.
 */
#ifndef vtkGlobalIlluminationDrawnColors_h
#define vtkGlobalIlluminationDrawnColors_h

#include "vtkSmartPointer.h"      // for vtkSmartPointer
#include "vtkUnsignedCharArray.h" // for vtkUnsignedCharArray

class vtkDataArray;
class vtkDataSet;
class vtkMapper;

namespace vtkGlobalIlluminationDrawnColors
{
/// Whether `mapper` colours through its lookup table (see above); `cells` says whether the
/// colouring array is a cell array.
bool MapsScalars(vtkMapper* mapper, bool& cells);

/// The colouring array of `data` as `mapper` would use it (null where the data lack it).
vtkDataArray* ColoringArray(vtkDataSet* data, vtkMapper* mapper, bool cells);

/// `scalars` through the mapper's lookup table: RGBA bytes, display (sRGB) values.
vtkSmartPointer<vtkUnsignedCharArray> Map(vtkMapper* mapper, vtkDataArray* scalars);
}

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationDrawnColors.h
