#include "vtkGlobalIlluminationDrawnAlbedo.h"

#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationColors.h"
#include "vtkGlobalIlluminationDrawnColors.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <sstream>
#include <string>

namespace
{
vtkDataSetAttributes* AttributesOf(vtkDataSet* data, bool cells)
{
  return cells ? static_cast<vtkDataSetAttributes*>(data->GetCellData()) : data->GetPointData();
}

/// `scalars` through the mapper's lookup table, times `diffuse`, as linear float RGB: the
/// table's colours are display (sRGB) values, which the filter would otherwise take as
/// linear reflectance.
vtkSmartPointer<vtkFloatArray> MappedColors(vtkMapper* mapper, vtkDataArray* scalars, double diffuse)
{
  auto rgba = vtkGlobalIlluminationDrawnColors::Map(mapper, scalars);
  auto colors = vtkSmartPointer<vtkFloatArray>::New();
  colors->SetName(vtkGlobalIlluminationDrawnAlbedo::GetMappedAlbedoName());
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(scalars->GetNumberOfTuples());
  for (vtkIdType i = 0; rgba && i < scalars->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double drawn = rgba->GetTypedComponent(i, c) / 255.0 * diffuse;
      const double linear = vtkGlobalIlluminationColors::ToLinear(drawn);
      colors->SetTypedComponent(i, c, static_cast<float>(linear));
    }
  }
  return colors;
}

/// A copy of `data` (its structure, shallow copies of its datasets) in which the datasets
/// that have the mapper's colouring array carry its colours.
vtkSmartPointer<vtkDataObject> WithMappedColors(vtkDataObject* data, vtkMapper* mapper, bool cells, double diffuse)
{
  const auto colored = [&](vtkDataSet* leaf) {
    auto copy = vtk::TakeSmartPointer(leaf->NewInstance());
    copy->ShallowCopy(leaf);
    if (vtkDataArray* scalars = vtkGlobalIlluminationDrawnColors::ColoringArray(copy, mapper, cells))
    {
      AttributesOf(copy, cells)->AddArray(MappedColors(mapper, scalars, diffuse));
    }
    return copy;
  };
  auto composite = vtkCompositeDataSet::SafeDownCast(data);
  if (!composite)
  {
    auto dataset = vtkDataSet::SafeDownCast(data);
    return dataset ? vtkSmartPointer<vtkDataObject>(colored(dataset)) : nullptr;
  }
  auto copy = vtk::TakeSmartPointer(composite->NewInstance());
  copy->CopyStructure(composite);
  auto it = vtk::TakeSmartPointer(composite->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    if (auto leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()))
    {
      copy->SetDataSet(it, colored(leaf));
    }
  }
  return copy;
}

bool AnyArray(vtkDataObject* data, const char* name, bool cells)
{
  for (vtkDataSet* leaf : vtkCompositeDataSet::GetDataSets<vtkDataSet>(data))
  {
    if (AttributesOf(leaf, cells)->GetArray(name))
    {
      return true;
    }
  }
  return false;
}
}

//------------------------------------------------------------------------------
struct vtkGlobalIlluminationDrawnAlbedo::vtkInternals
{
  // The data with the mapped colours, remade only when the data or the colouring change.
  vtkSmartPointer<vtkDataObject> Colored;
  vtkDataObject* ColoredFrom = nullptr;
  vtkMTimeType ColoredTime = 0;
  std::string ColoredKey;
};

vtkStandardNewMacro(vtkGlobalIlluminationDrawnAlbedo);

//------------------------------------------------------------------------------
vtkGlobalIlluminationDrawnAlbedo::vtkGlobalIlluminationDrawnAlbedo()
  : Internals(new vtkInternals)
{
  this->SetAlbedoArrayName("Albedo");
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationDrawnAlbedo::~vtkGlobalIlluminationDrawnAlbedo()
{
  this->SetAlbedoArrayName(nullptr);
}

//------------------------------------------------------------------------------
vtkDataObject* vtkGlobalIlluminationDrawnAlbedo::Apply(vtkDataObject* data, vtkMapper* mapper,
  vtkProperty* property, vtkGlobalIlluminationFilter* filter)
{
  if (!data || !mapper || !property || !filter)
  {
    return data;
  }
  const double diffuse = property->GetDiffuse();
  double color[3];
  property->GetDiffuseColor(color);
  // The solid colour is a display (sRGB) value; the filter's albedo is linear.
  const auto linear = [&](int c)
  { return vtkGlobalIlluminationColors::ToLinear(color[c] * diffuse); };
  filter->SetAlbedo(linear(0), linear(1), linear(2));
  filter->SetAlbedoArrayAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);

  // The mapper's own albedo array comes first, as in its shaders.
  const char* albedo = this->AlbedoArrayName;
  if (albedo && *albedo && AnyArray(data, albedo, false))
  {
    filter->SetAlbedoArrayName(albedo);
    return data;
  }
  bool cells = false;
  if (!vtkGlobalIlluminationDrawnColors::MapsScalars(mapper, cells))
  {
    filter->SetAlbedoArrayName(nullptr);
    return data;
  }
  const char* colorArray = mapper->GetArrayName();
  vtkInternals& internals = *this->Internals;
  vtkScalarsToColors* table = mapper->GetLookupTable();
  // Built now, as the mapper builds it when it first draws: a colour transfer function's
  // build moves its time (its internal table) but not its colours, and would otherwise
  // remake the colours and the mapper's buffers at the second render.
  table->Build();
  std::ostringstream key;
  key << colorArray << '|' << cells << '|' << table << '|' << table->GetMTime() << '|'
      << mapper->GetColorMode() << '|' << mapper->GetArrayComponent() << '|' << diffuse;
  if (data != internals.ColoredFrom || data->GetMTime() != internals.ColoredTime ||
    key.str() != internals.ColoredKey)
  {
    internals.Colored = WithMappedColors(data, mapper, cells, diffuse);
    internals.ColoredFrom = data;
    internals.ColoredTime = data->GetMTime();
    internals.ColoredKey = key.str();
  }
  // Blocks without the colouring array get the solid colour; with none at all, all do.
  const bool any = AnyArray(internals.Colored, GetMappedAlbedoName(), cells);
  filter->SetAlbedoArrayName(any ? GetMappedAlbedoName() : nullptr);
  filter->SetAlbedoArrayAssociation(
    cells ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS);
  return internals.Colored;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationDrawnAlbedo::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Albedo Array Name: " << (this->AlbedoArrayName ? this->AlbedoArrayName : "(none)") << "\n";
}
