// Inputs that fuzzing (Testing/Fuzz) found to break the filter, kept as regression tests.
#include "FilterTestUtilities.h"

#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkCellArray.h"
#include "vtkPoints.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
/// Four points of a unit square in z = 0, lit from above.
vtkSmartPointer<vtkPolyData> Square()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(1, 1, 0);
  pd->SetPoints(points);
  return pd;
}
}

TEST(FuzzFindings, StripsOfFewerThanThreePointsAreSkipped)
{
  // vtkTriangleFilter (VTK 9.1) reads the first point of every strip: a strip array that
  // holds only empty strips has no point storage at all, and that read crashed. Strips of
  // 0, 1 and 2 points hold no triangle; a 4-point strip after them gives two, whose cell
  // ids must still be its own.
  const vtkIdType triangle[3] = { 0, 1, 2 }, strip[4] = { 0, 1, 2, 3 }, two[2] = { 0, 1 };
  for (const bool onlyEmpty : { true, false })
  {
    SCOPED_TRACE(onlyEmpty ? "one empty strip" : "strips of 0, 1, 2 and 4 points");
    vtkSmartPointer<vtkPolyData> pd = Square();
    vtkNew<vtkCellArray> polys, strips;
    polys->InsertNextCell(3, triangle);
    strips->InsertNextCell(0, triangle);
    if (!onlyEmpty)
    {
      strips->InsertNextCell(1, triangle);
      strips->InsertNextCell(2, two);
      strips->InsertNextCell(4, strip);
    }
    pd->SetPolys(polys);
    pd->SetStrips(strips);

    const vtkGlobalIlluminationSceneBuilder::Mesh mesh =
      vtkGlobalIlluminationSceneBuilder::BuildMesh(pd, true, 30.0);
    // Cell 0 is the polygon, cells 1.. the strips.
    const std::vector<vtkIdType> cells =
      onlyEmpty ? std::vector<vtkIdType>{ 0 } : std::vector<vtkIdType>{ 0, 4, 4 };
    EXPECT_EQ(mesh.TriangleCell, cells);

    vtkNew<vtkGlobalIlluminationFilter> filter;
    filter->SetInputData(pd);
    filter->SetRaysPerVertex(16);
    filter->Update();
    vtkDataArray* radiance = PointArray(filter->GetOutput(), "Radiance");
    ASSERT_NE(radiance, nullptr);
    EXPECT_EQ(radiance->GetNumberOfTuples(), 4);
  }
}
