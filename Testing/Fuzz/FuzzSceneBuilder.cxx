// libFuzzer target: the VTK scene builder on random vtkPolyData - NaN, infinite and huge
// coordinates in float or double points; vertices, lines, polygons and strips of every
// size; point and cell arrays of every type and component count, of the right size or
// not, with names that collide (the albedo's name twice, in point and cell data, as the
// normals). vtkGlobalIlluminationSceneBuilder either throws linkgi::Error or builds a mesh
// whose maps point into the input, and the colours it gathers are one per element.
#include "FuzzInput.h"

#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkBitArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include "linkgi/Error.h"

#include <cmath>
#include <cstdlib>

using linkgi_fuzz::Input;

namespace
{
const char* const kNames[] = { "Albedo", "Emission", "Normals", "Colors", "" };

vtkSmartPointer<vtkAbstractArray> makeArray(Input& in, vtkIdType tuples)
{
  vtkSmartPointer<vtkAbstractArray> a;
  switch (in.count(10))
  {
    case 0: a = vtkSmartPointer<vtkFloatArray>::New(); break;
    case 1: a = vtkSmartPointer<vtkDoubleArray>::New(); break;
    case 2: a = vtkSmartPointer<vtkIntArray>::New(); break;
    case 3: a = vtkSmartPointer<vtkUnsignedCharArray>::New(); break;
    case 4: a = vtkSmartPointer<vtkCharArray>::New(); break;
    case 5: a = vtkSmartPointer<vtkShortArray>::New(); break;
    case 6: a = vtkSmartPointer<vtkUnsignedShortArray>::New(); break;
    case 7: a = vtkSmartPointer<vtkTypeInt64Array>::New(); break;
    case 8: a = vtkSmartPointer<vtkIdTypeArray>::New(); break;
    case 9: a = vtkSmartPointer<vtkBitArray>::New(); break;
    default: a = vtkSmartPointer<vtkStringArray>::New(); break;
  }
  a->SetNumberOfComponents(1 + int(in.count(4)));
  a->SetName(kNames[in.count(4)]);
  a->SetNumberOfTuples(tuples);
  const vtkIdType values = tuples * a->GetNumberOfComponents();
  if (auto* numbers = vtkDataArray::SafeDownCast(a))
  {
    for (vtkIdType i = 0; i < values; ++i)
    {
      // SetComponent converts as the array's type does (NaN to an integer array: 0).
      const double v = in.real();
      numbers->SetComponent(i / numbers->GetNumberOfComponents(),
        int(i % numbers->GetNumberOfComponents()), numbers->GetDataType() == VTK_DOUBLE ||
            numbers->GetDataType() == VTK_FLOAT || std::isfinite(v)
          ? v
          : 0.0);
    }
  }
  else
  {
    auto* strings = vtkStringArray::SafeDownCast(a);
    for (vtkIdType i = 0; i < values; ++i)
    {
      strings->SetValue(i, in.boolean() ? "0.5" : "red");
    }
  }
  return a;
}

void addArrays(Input& in, vtkDataSetAttributes* attributes, vtkIdType nominal)
{
  for (std::size_t k = in.count(3); k > 0; --k)
  {
    const vtkIdType tuples = vtkIdType(linkgi_fuzz::sizeNear(in, std::size_t(nominal)));
    vtkSmartPointer<vtkAbstractArray> a = makeArray(in, tuples);
    if (in.count(3) == 0)
    {
      attributes->SetNormals(vtkDataArray::SafeDownCast(a)); // refused unless 3 components
    }
    else
    {
      attributes->AddArray(a); // replaces an array of the same name
    }
  }
}

vtkSmartPointer<vtkPolyData> makePolyData(Input& in)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(in.boolean() ? VTK_FLOAT : VTK_DOUBLE);
  const vtkIdType n = vtkIdType(in.count(24));
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double x = in.real(), y = in.real();
    points->SetPoint(i, x, y, in.real());
  }
  pd->SetPoints(points);
  vtkNew<vtkCellArray> cells[4]; // vertices, lines, polygons, strips
  for (vtkCellArray* c : cells)
  {
    for (std::size_t k = in.count(8); k > 0; --k)
    {
      const vtkIdType size = vtkIdType(in.count(7));
      c->InsertNextCell(size);
      for (vtkIdType j = 0; j < size; ++j)
      {
        c->InsertCellPoint(n ? vtkIdType(in.count(std::size_t(n - 1))) : 0);
      }
    }
  }
  if (n == 0)
  {
    for (vtkCellArray* c : cells)
    {
      c->Reset(); // a cell needs points to refer to
    }
  }
  pd->SetVerts(cells[0]);
  pd->SetLines(cells[1]);
  pd->SetPolys(cells[2]);
  pd->SetStrips(cells[3]);
  addArrays(in, pd->GetPointData(), n);
  addArrays(in, pd->GetCellData(), pd->GetNumberOfCells());
  return pd;
}
}

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // Warnings of VTK's own filters about odd input are expected here, not findings.
  vtkObject::GlobalWarningDisplayOff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  vtkSmartPointer<vtkPolyData> pd = makePolyData(in);
  const bool computeNormals = in.boolean();
  const double featureAngle = in.real();
  try
  {
    const vtkGlobalIlluminationSceneBuilder::Mesh mesh =
      vtkGlobalIlluminationSceneBuilder::BuildMesh(pd, computeNormals, featureAngle);
    const std::size_t elements = mesh.Scene.vertexCount();
    LINKGI_FUZZ_REQUIRE(mesh.ElementPoint.size() == elements);
    LINKGI_FUZZ_REQUIRE(mesh.TriangleCell.size() == mesh.Scene.triangleCount());
    for (vtkIdType p : mesh.ElementPoint)
    {
      LINKGI_FUZZ_REQUIRE(p >= 0 && p < pd->GetNumberOfPoints());
    }
    for (vtkIdType c : mesh.TriangleCell)
    {
      LINKGI_FUZZ_REQUIRE(c >= 0 && c < pd->GetNumberOfCells());
    }
    const int association = in.boolean() ? vtkDataObject::FIELD_ASSOCIATION_POINTS
                                          : vtkDataObject::FIELD_ASSOCIATION_CELLS;
    const char* name = in.boolean() ? kNames[in.count(4)] : nullptr;
    const std::vector<linkgi::Vec3f> colors = vtkGlobalIlluminationSceneBuilder::GatherColors(
      pd, mesh, name, association, linkgi::Vec3f(0.5f), "albedo");
    LINKGI_FUZZ_REQUIRE(colors.size() == elements);
    const std::vector<linkgi::Vec3f> values(elements, linkgi::Vec3f(1.f));
    vtkSmartPointer<vtkFloatArray> mapped =
      vtkGlobalIlluminationSceneBuilder::MapToPoints(mesh, values, 0, "Radiance");
    LINKGI_FUZZ_REQUIRE(mapped->GetNumberOfTuples() == pd->GetNumberOfPoints());
  }
  catch (const linkgi::Error&)
  {
  }
  return 0;
}
