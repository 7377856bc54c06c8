#include "vtkGlobalIlluminationBlockMerger.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkFloatArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <sstream>

namespace
{
/// The polydata leaves of `data`, in traversal order (the order the output keeps).
std::vector<vtkPolyData*> PolyDataLeaves(vtkDataObject* data)
{
  std::vector<vtkPolyData*> leaves;
  if (auto poly = vtkPolyData::SafeDownCast(data))
  {
    leaves.push_back(poly);
  }
  else if (auto tree = vtkDataObjectTree::SafeDownCast(data))
  {
    vtkSmartPointer<vtkDataObjectTreeIterator> it;
    it.TakeReference(tree->NewTreeIterator());
    it->VisitOnlyLeavesOn();
    it->SkipEmptyNodesOn();
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
      {
        leaves.push_back(leaf);
      }
    }
  }
  return leaves;
}

/// A float RGB array of `n` tuples, all `rgb`.
vtkSmartPointer<vtkFloatArray> Constant(const char* name, vtkIdType n, const double rgb[3])
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(n);
  for (int c = 0; c < 3; ++c)
  {
    array->FillComponent(c, rgb[c]);
  }
  return array;
}

bool HasRGB(vtkPolyData* leaf, const char* name)
{
  vtkDataArray* array = leaf->GetPointData()->GetArray(name);
  return array && array->GetNumberOfComponents() >= 3;
}
}

//------------------------------------------------------------------------------
std::string vtkGlobalIlluminationBlockMerger::Albedo::Key() const
{
  std::ostringstream key;
  key << this->MapScalars << '|' << this->ArrayName << '|' << this->Association << '|'
      << this->LookupTable << '|' << (this->LookupTable ? this->LookupTable->GetMTime() : 0)
      << '|' << this->ColorMode << '|' << this->Component << '|' << this->Color[0] << ','
      << this->Color[1] << ',' << this->Color[2] << '|' << this->Diffuse;
  return key.str();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkGlobalIlluminationBlockMerger::Strip(
  vtkPolyData* leaf, const Albedo& albedo, bool withNormals, bool withEmission) const
{
  // Geometry and exactly the arrays the filter reads, identical on every leaf (the append
  // keeps only the arrays that all its inputs have).
  auto stripped = vtkSmartPointer<vtkPolyData>::New();
  stripped->SetPoints(leaf->GetPoints());
  stripped->SetVerts(leaf->GetVerts());
  stripped->SetLines(leaf->GetLines());
  stripped->SetPolys(leaf->GetPolys());
  stripped->SetStrips(leaf->GetStrips());
  if (withNormals)
  {
    stripped->GetPointData()->SetNormals(leaf->GetPointData()->GetNormals());
  }
  if (withEmission)
  {
    const double black[3] = { 0.0, 0.0, 0.0 };
    vtkDataArray* emission = leaf->GetPointData()->GetArray("Emission");
    if (emission && emission->GetNumberOfComponents() >= 3)
    {
      stripped->GetPointData()->AddArray(emission);
    }
    else
    {
      stripped->GetPointData()->AddArray(Constant("Emission", leaf->GetNumberOfPoints(), black));
    }
  }
  if (this->AlbedoAssociation < 0)
  {
    return stripped;
  }

  const bool cells = this->AlbedoAssociation == 1;
  vtkDataSetAttributes* attributes = cells ? static_cast<vtkDataSetAttributes*>(leaf->GetCellData())
                                           : static_cast<vtkDataSetAttributes*>(leaf->GetPointData());
  vtkDataSetAttributes* target = cells ? static_cast<vtkDataSetAttributes*>(stripped->GetCellData())
                                       : static_cast<vtkDataSetAttributes*>(stripped->GetPointData());
  const vtkIdType n = cells ? leaf->GetNumberOfCells() : leaf->GetNumberOfPoints();
  const double scaled[3] = { albedo.Color[0] * albedo.Diffuse, albedo.Color[1] * albedo.Diffuse,
    albedo.Color[2] * albedo.Diffuse };
  vtkSmartPointer<vtkFloatArray> out = Constant(AlbedoArrayName(), n, scaled);

  vtkDataArray* source = attributes->GetArray(albedo.MapScalars ? albedo.ArrayName.c_str() : "Albedo");
  if (source && albedo.MapScalars && albedo.LookupTable)
  {
    // The colours the mapper draws, times Diffuse, as the mapper's albedo.
    vtkSmartPointer<vtkUnsignedCharArray> rgba;
    rgba.TakeReference(
      albedo.LookupTable->MapScalars(source, albedo.ColorMode, albedo.Component, VTK_RGBA));
    for (vtkIdType i = 0; rgba && i < n; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        out->SetTypedComponent(i, c, rgba->GetTypedComponent(i, c) / 255.f * albedo.Diffuse);
      }
    }
  }
  else if (source && !albedo.MapScalars && source->GetNumberOfComponents() >= 3)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        out->SetTypedComponent(i, c, static_cast<float>(source->GetComponent(i, c)));
      }
    }
  }
  target->AddArray(out);
  return stripped;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationBlockMerger::Merge(vtkDataObject* data, const Albedo& albedo)
{
  const std::string key = albedo.Key();
  if (data == this->Input && data && data->GetMTime() == this->InputTime && key == this->AlbedoKey)
  {
    return false;
  }
  this->Input = data;
  this->InputTime = data ? data->GetMTime() : 0;
  this->AlbedoKey = key;

  const std::vector<vtkPolyData*> leaves = PolyDataLeaves(data);
  bool allNormals = !leaves.empty(), anyEmission = false, anyAlbedo = false;
  for (vtkPolyData* leaf : leaves)
  {
    vtkDataArray* normals = leaf->GetPointData()->GetNormals();
    allNormals = allNormals && normals && normals->GetNumberOfComponents() == 3;
    anyEmission = anyEmission || HasRGB(leaf, "Emission");
    anyAlbedo = anyAlbedo || HasRGB(leaf, "Albedo");
  }
  // An `Albedo` point array (LinkGI's convention) is the albedo, as for the mapper; else
  // the mapped colours; else the solid colour, which needs no array.
  this->AlbedoAssociation = -1;
  if (anyAlbedo && !albedo.MapScalars)
  {
    this->AlbedoAssociation = 0;
  }
  else if (albedo.MapScalars)
  {
    this->AlbedoAssociation = albedo.Association == 1 ? 1 : 0;
  }
  this->Emission = anyEmission;

  vtkNew<vtkAppendPolyData> append;
  this->Leaves.clear();
  long long firstPoint = 0;
  for (vtkPolyData* leaf : leaves)
  {
    Leaf entry;
    entry.Input = leaf;
    entry.Output = vtkSmartPointer<vtkPolyData>::New();
    entry.Output->ShallowCopy(leaf);
    entry.FirstPoint = firstPoint;
    firstPoint += leaf->GetNumberOfPoints();
    this->Leaves.push_back(entry);
    append->AddInputData(this->Strip(leaf, albedo, allNormals, anyEmission));
  }
  if (leaves.empty())
  {
    this->Merged->Initialize();
  }
  else
  {
    append->Update();
    this->Merged->ShallowCopy(append->GetOutput());
  }

  // The same structure as the input, with the output leaves in place of the input's.
  if (auto composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    this->Output.TakeReference(composite->NewInstance());
    this->Output->ShallowCopy(composite);
    auto tree = vtkDataObjectTree::SafeDownCast(this->Output);
    vtkSmartPointer<vtkDataObjectTreeIterator> it;
    it.TakeReference(tree->NewTreeIterator());
    it->VisitOnlyLeavesOn();
    it->SkipEmptyNodesOn();
    std::size_t index = 0;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (vtkPolyData::SafeDownCast(it->GetCurrentDataObject()) && index < this->Leaves.size())
      {
        tree->SetDataSet(it, this->Leaves[index++].Output);
      }
    }
  }
  else
  {
    this->Output = this->Leaves.empty() ? nullptr : this->Leaves[0].Output;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationBlockMerger::Scatter(
  vtkPolyData* lit, const std::vector<std::string>& names)
{
  for (const std::string& name : names)
  {
    vtkDataArray* source = lit ? lit->GetPointData()->GetArray(name.c_str()) : nullptr;
    for (Leaf& leaf : this->Leaves)
    {
      const vtkIdType n = leaf.Input->GetNumberOfPoints();
      if (!source || source->GetNumberOfTuples() < leaf.FirstPoint + n)
      {
        leaf.Output->GetPointData()->RemoveArray(name.c_str());
        continue;
      }
      vtkNew<vtkFloatArray> slice;
      slice->SetName(name.c_str());
      slice->SetNumberOfComponents(source->GetNumberOfComponents());
      slice->SetNumberOfTuples(n);
      for (vtkIdType i = 0; i < n; ++i)
      {
        slice->SetTuple(i, leaf.FirstPoint + i, source);
      }
      leaf.Output->GetPointData()->AddArray(slice);
    }
  }
}

//------------------------------------------------------------------------------
long long vtkGlobalIlluminationBlockMerger::GetNumberOfPoints() const
{
  return this->Merged->GetNumberOfPoints();
}
