// vtkGlobalIlluminationDrawnAlbedo: the filter's albedo is what the mapper draws - the
// mapper's Albedo point array, else the colouring array through the lookup table (point or
// cell scalars, per block), else the solid colour, times Diffuse; the mapped copy is kept
// while nothing changes.
#include "RenderingTestUtilities.h"
#include "vtkGlobalIlluminationColors.h"

#include "vtkCellData.h"
#include "vtkDiscretizableColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkGlobalIlluminationDrawnAlbedo.h"
#include "vtkLookupTable.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkProperty.h"

#include <cmath>

namespace
{
vtkSmartPointer<vtkPolyData> Plane(bool withScalars)
{
  vtkNew<vtkPlaneSource> source;
  source->SetResolution(2, 2);
  source->Update();
  auto plane = vtkSmartPointer<vtkPolyData>::New();
  plane->DeepCopy(source->GetOutput());
  if (withScalars)
  {
    vtkNew<vtkDoubleArray> data;
    data->SetName("Data");
    for (vtkIdType i = 0; i < plane->GetNumberOfPoints(); ++i)
    {
      data->InsertNextValue(i % 2); // 0 -> the table's first colour, 1 -> its last
    }
    plane->GetPointData()->AddArray(data);
    vtkNew<vtkDoubleArray> cellData;
    cellData->SetName("Data");
    for (vtkIdType i = 0; i < plane->GetNumberOfCells(); ++i)
    {
      cellData->InsertNextValue(1.0);
    }
    plane->GetCellData()->AddArray(cellData);
  }
  return plane;
}

bool Near(double a, double b)
{
  return std::abs(a - b) < 1e-6;
}
}

int TestGlobalIlluminationDrawnAlbedo(int, char*[])
{
  using namespace linkgi_test;
  bool ok = true;
  vtkNew<vtkLookupTable> table; // red at 0, blue at 1
  table->SetNumberOfTableValues(2);
  table->SetTableValue(0, 1, 0, 0);
  table->SetTableValue(1, 0, 0, 1);
  table->SetTableRange(0, 1);
  table->Build();
  vtkNew<vtkGlobalIlluminationMapper> mapper;
  mapper->SetLookupTable(table);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("Data");
  mapper->ScalarVisibilityOn();
  vtkNew<vtkProperty> property;
  property->SetDiffuseColor(0.2, 0.4, 0.6);
  property->SetDiffuse(0.5);
  vtkNew<vtkGlobalIlluminationFilter> gi;
  vtkNew<vtkGlobalIlluminationDrawnAlbedo> drawn;
  const char* mapped = vtkGlobalIlluminationDrawnAlbedo::GetMappedAlbedoName();

  // Point scalars through the table, times Diffuse, on a copy; the input is untouched.
  auto plane = Plane(true);
  vtkDataObject* input = drawn->Apply(plane, mapper, property, gi);
  auto* lit = vtkPolyData::SafeDownCast(input);
  vtkDataArray* colors = lit ? lit->GetPointData()->GetArray(mapped) : nullptr;
  ok &= Check(input != plane && colors && !plane->GetPointData()->GetArray(mapped),
    "colouring by an array gives a copy with the mapped colours");
  ok &= Check(gi->GetAlbedoArrayName() && std::string(gi->GetAlbedoArrayName()) == mapped &&
      gi->GetAlbedoArrayAssociation() == vtkDataObject::FIELD_ASSOCIATION_POINTS,
    "the filter reads the mapped colours as point albedo");
  // Drawn colours are display (sRGB) values; the filter gets them as linear reflectance.
  const auto linear = [](double drawnValue)
  { return vtkGlobalIlluminationColors::ToLinear(drawnValue); };
  ok &= Check(colors && Near(colors->GetComponent(0, 0), linear(0.5)) &&
      Near(colors->GetComponent(0, 2), 0.0) && Near(colors->GetComponent(1, 0), 0.0) &&
      Near(colors->GetComponent(1, 2), linear(0.5)),
    "red and blue from the table, times Diffuse 0.5, linear");
  double solid[3];
  gi->GetAlbedo(solid);
  ok &= Check(
    Near(solid[0], linear(0.1)) && Near(solid[1], linear(0.2)) && Near(solid[2], linear(0.3)),
    "the solid colour times Diffuse for what has no array, linear");
  ok &= Check(drawn->Apply(plane, mapper, property, gi) == input, "unchanged input: the copy is kept");
  table->SetTableValue(1, 0, 1, 0);
  vtkDataObject* recolored = drawn->Apply(plane, mapper, property, gi);
  vtkDataArray* green = vtkPolyData::SafeDownCast(recolored)->GetPointData()->GetArray(mapped);
  ok &= Check(
    Near(green->GetComponent(1, 1), linear(0.5)), "a changed table is mapped again");

  // A colour transfer function builds its internal table when it first maps (the mapper's
  // draw), which moves its time but not its colours: the copy is kept (a new one would
  // rebuild every vertex buffer of the next frame). A new colour still maps again.
  vtkNew<vtkDiscretizableColorTransferFunction> function;
  function->AddRGBPoint(0.0, 1.0, 0.0, 0.0);
  function->AddRGBPoint(1.0, 0.0, 0.0, 1.0);
  mapper->SetLookupTable(function);
  vtkDataObject* first = drawn->Apply(plane, mapper, property, gi);
  function->Build(); // what the mapper's first draw does
  ok &= Check(drawn->Apply(plane, mapper, property, gi) == first,
    "a colour transfer function built by a draw: the copy is kept");
  function->AddRGBPoint(1.0, 0.0, 1.0, 0.0);
  green = vtkPolyData::SafeDownCast(drawn->Apply(plane, mapper, property, gi))->GetPointData()->GetArray(mapped);
  ok &= Check(Near(green->GetComponent(1, 1), linear(0.5)) && Near(green->GetComponent(1, 2), 0.0),
    "a changed colour transfer function is mapped again");
  mapper->SetLookupTable(table);

  // Cell scalars.
  mapper->SetScalarModeToUseCellFieldData();
  lit = vtkPolyData::SafeDownCast(drawn->Apply(plane, mapper, property, gi));
  ok &= Check(lit && lit->GetCellData()->GetArray(mapped) &&
      gi->GetAlbedoArrayAssociation() == vtkDataObject::FIELD_ASSOCIATION_CELLS,
    "cell scalars give cell albedo");
  mapper->SetScalarModeToUsePointFieldData();

  // The mapper's own Albedo array wins, as in its shaders.
  vtkNew<vtkDoubleArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(plane->GetNumberOfPoints());
  albedo->Fill(0.25);
  plane->GetPointData()->AddArray(albedo);
  ok &= Check(drawn->Apply(plane, mapper, property, gi) == plane &&
      std::string(gi->GetAlbedoArrayName()) == "Albedo",
    "an Albedo point array is the albedo, on the input itself");
  plane->GetPointData()->RemoveArray("Albedo");

  // Scalar visibility off: the solid colour only.
  mapper->ScalarVisibilityOff();
  ok &= Check(drawn->Apply(plane, mapper, property, gi) == plane && !gi->GetAlbedoArrayName(),
    "without scalar colouring the solid colour");
  mapper->ScalarVisibilityOn();

  // Composite: the block with the array gets mapped colours, the other the solid colour.
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, Plane(true));
  blocks->SetBlock(1, Plane(false));
  auto* coloredBlocks = vtkMultiBlockDataSet::SafeDownCast(drawn->Apply(blocks, mapper, property, gi));
  ok &= Check(coloredBlocks && coloredBlocks != blocks.Get() && coloredBlocks->GetNumberOfBlocks() == 2 &&
      vtkPolyData::SafeDownCast(coloredBlocks->GetBlock(0))->GetPointData()->GetArray(mapped) &&
      !vtkPolyData::SafeDownCast(coloredBlocks->GetBlock(1))->GetPointData()->GetArray(mapped) &&
      std::string(gi->GetAlbedoArrayName()) == mapped,
    "per block: mapped colours where the array is, the solid colour elsewhere");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
