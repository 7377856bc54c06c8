/**
 * @class   vtkGlobalIlluminationGeometry
 * @brief   what a surface's geometry is read from: the one rule of the filter (when to build
 *          its triangle mesh again) and the mappers (when to render their shadow maps again)
 *
 * Sources: the points, the polygons and strips with their storage (VTK 9.1's cell arrays
 * leave their offsets and connectivity out of their own modification time), the verts and
 * lines (their counts number the cell ids) and the point normals. The geometry changes only
 * when one of them is replaced or modified; a new data object that shares them (a shallow
 * copy with a new colour array from a colour map, or with a new solution's irradiance) is
 * the same surface.
 *
 * Part of LinkGI::FiltersGlobalIllumination, used by LinkGI::RenderingGlobalIllumination.
 * Not wrapped.
 */
#ifndef vtkGlobalIlluminationGeometry_h
#define vtkGlobalIlluminationGeometry_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro

#include <vector> // for std::vector

class vtkObject;
class vtkPolyData;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationGeometry
{
public:
  /// The objects `surface`'s geometry is read from (none for null), in a fixed order.
  static std::vector<vtkObject*> Sources(vtkPolyData* surface);
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationGeometry.h
