#include "vtkGlobalIlluminationGeometry.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

//------------------------------------------------------------------------------
std::vector<vtkObject*> vtkGlobalIlluminationGeometry::Sources(vtkPolyData* surface)
{
  if (!surface)
  {
    return {};
  }
  vtkCellArray* polys = surface->GetPolys();
  vtkCellArray* strips = surface->GetStrips();
  return { surface->GetPoints(), polys, polys->GetOffsetsArray(), polys->GetConnectivityArray(),
    strips, strips->GetOffsetsArray(), strips->GetConnectivityArray(), surface->GetVerts(),
    surface->GetLines(), surface->GetPointData()->GetNormals() };
}
