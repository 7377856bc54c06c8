#include "vtkGlobalIlluminationBlockMerger.h"

#include "vtkGlobalIlluminationColors.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDataObjectTree.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <sstream>

namespace
{
/// Calls `visit(leaf)` for the non-empty leaves of `data` in traversal order (a dataset
/// that is no tree is its own one leaf).
template <typename Visit>
void ForEachLeaf(vtkDataObject* data, Visit&& visit)
{
  auto tree = vtkDataObjectTree::SafeDownCast(data);
  if (!tree)
  {
    if (data)
    {
      visit(data);
    }
    return;
  }
  auto it = vtk::TakeSmartPointer(tree->NewTreeIterator());
  it->VisitOnlyLeavesOn();
  it->SkipEmptyNodesOn();
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    visit(it->GetCurrentDataObject());
  }
}

/// The newest modification time of `data` and its leaves.
vtkMTimeType NewestTime(vtkDataObject* data)
{
  vtkMTimeType newest = data ? data->GetMTime() : 0;
  ForEachLeaf(data, [&](vtkDataObject* leaf) { newest = std::max(newest, leaf->GetMTime()); });
  return newest;
}

vtkDataSetAttributes* AttributesOf(vtkPolyData* data, int association)
{
  if (association == vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    return data->GetCellData();
  }
  return data->GetPointData();
}

/// `rgb` as a float RGB array of `n` tuples named `name`.
vtkSmartPointer<vtkFloatArray> Constant(const std::string& name, vtkIdType n, const double rgb[3])
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(n);
  for (int c = 0; c < 3; ++c)
  {
    array->FillComponent(c, rgb[c]);
  }
  return array;
}

/// The leaf's colour array `carried` as float RGB (the fallback where it has none).
vtkSmartPointer<vtkFloatArray> CarriedColors(
  vtkPolyData* leaf, std::size_t index, const vtkGlobalIlluminationBlockMerger::Carried& carried)
{
  const bool cells = carried.Association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const vtkIdType n = cells ? leaf->GetNumberOfCells() : leaf->GetNumberOfPoints();
  auto out = Constant(carried.Name, n, carried.Fallback.data());
  vtkDataArray* source = AttributesOf(leaf, carried.Association)->GetArray(carried.Name.c_str());
  if (!source)
  {
    return out;
  }
  if (source->GetNumberOfTuples() < n || source->GetNumberOfComponents() < 1)
  {
    std::ostringstream msg;
    msg << "The " << carried.Role << " array '" << carried.Name << "' of block " << index
        << " has " << source->GetNumberOfTuples() << " tuples, but the block has " << n
        << (cells ? " cells." : " points.");
    throw linkgi::Error(msg.str());
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkGlobalIlluminationColors::RGB rgb = vtkGlobalIlluminationColors::Read(source, i);
    out->SetTuple(i, rgb.data());
  }
  return out;
}
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationBlockMerger::CollectLeaves(vtkDataObject* data)
{
  this->Leaves.clear();
  vtkIdType firstPoint = 0;
  ForEachLeaf(data, [&](vtkDataObject* object) {
    Leaf leaf;
    leaf.Input = vtkPolyData::SafeDownCast(object);
    if (!leaf.Input)
    {
      auto* dataset = vtkDataSet::SafeDownCast(object);
      if (!dataset)
      {
        return; // not a dataset (e.g. a table): nothing to light, left as it is
      }
      vtkNew<vtkDataSetSurfaceFilter> surface;
      surface->SetInputData(dataset);
      surface->Update();
      leaf.Input = surface->GetOutput();
    }
    leaf.Output = vtkSmartPointer<vtkPolyData>::New();
    leaf.Output->ShallowCopy(leaf.Input);
    leaf.FirstPoint = firstPoint;
    firstPoint += leaf.Input->GetNumberOfPoints();
    this->Leaves.push_back(leaf);
  });
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkGlobalIlluminationBlockMerger::Strip(
  const Leaf& leaf, std::size_t index, bool withNormals) const
{
  // Geometry and exactly the arrays the filter reads, on every leaf: the append keeps only
  // the arrays that all its inputs have.
  vtkPolyData* in = leaf.Input;
  auto stripped = vtkSmartPointer<vtkPolyData>::New();
  stripped->SetPoints(in->GetPoints());
  stripped->SetVerts(in->GetVerts());
  stripped->SetLines(in->GetLines());
  stripped->SetPolys(in->GetPolys());
  stripped->SetStrips(in->GetStrips());
  if (withNormals)
  {
    stripped->GetPointData()->SetNormals(in->GetPointData()->GetNormals());
  }
  for (const Carried& carried : this->CarriedArrays)
  {
    AttributesOf(stripped, carried.Association)->AddArray(CarriedColors(in, index, carried));
  }
  return stripped;
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationBlockMerger::Merge(
  vtkDataObject* data, const std::vector<Carried>& carried)
{
  const vtkMTimeType time = NewestTime(data);
  if (data && data == this->Input && time == this->InputTime && carried == this->CarriedArrays)
  {
    return false;
  }
  this->Input = nullptr; // until the merge succeeded
  this->CarriedArrays = carried;
  this->CollectLeaves(data);

  bool allNormals = true;
  std::vector<bool> found(carried.size(), false);
  for (const Leaf& leaf : this->Leaves)
  {
    vtkDataArray* normals = leaf.Input->GetPointData()->GetNormals();
    const bool empty = leaf.Input->GetNumberOfPoints() == 0;
    allNormals = allNormals && (empty || (normals && normals->GetNumberOfComponents() == 3));
  }
  vtkNew<vtkAppendPolyData> append;
  for (std::size_t i = 0; i < this->Leaves.size(); ++i)
  {
    if (this->Leaves[i].Input->GetNumberOfPoints() == 0)
    {
      continue; // contributes nothing, and would make the append drop arrays
    }
    append->AddInputData(this->Strip(this->Leaves[i], i, allNormals));
    for (std::size_t c = 0; c < carried.size(); ++c)
    {
      vtkDataSetAttributes* attributes = AttributesOf(this->Leaves[i].Input, carried[c].Association);
      found[c] = found[c] || attributes->GetArray(carried[c].Name.c_str()) != nullptr;
    }
  }
  for (std::size_t c = 0; c < carried.size(); ++c)
  {
    if (!found[c] && append->GetNumberOfInputConnections(0) > 0)
    {
      const bool cells = carried[c].Association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
      throw linkgi::Error("The " + carried[c].Role + " array '" + carried[c].Name +
        "' is not a numeric array of the " + (cells ? "cell" : "point") +
        " data of any block; check the array name and association.");
    }
  }
  if (append->GetNumberOfInputConnections(0) == 0)
  {
    this->Merged->Initialize();
  }
  else
  {
    append->Update();
    this->Merged->ShallowCopy(append->GetOutput());
  }
  this->BuildStructure(data);
  this->Input = data;
  this->InputTime = time;
  return true;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationBlockMerger::BuildStructure(vtkDataObject* data)
{
  auto tree = vtkDataObjectTree::SafeDownCast(data);
  if (!tree)
  {
    this->Structure = this->Leaves.empty() ? nullptr : this->Leaves[0].Output;
    return;
  }
  // ShallowCopy clones nested trees, so replacing leaves leaves the input alone.
  this->Structure = vtk::TakeSmartPointer(tree->NewInstance());
  this->Structure->ShallowCopy(tree);
  auto output = vtkDataObjectTree::SafeDownCast(this->Structure);
  auto it = vtk::TakeSmartPointer(output->NewTreeIterator());
  it->VisitOnlyLeavesOn();
  it->SkipEmptyNodesOn();
  std::size_t index = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    if (vtkDataSet::SafeDownCast(it->GetCurrentDataObject()) && index < this->Leaves.size())
    {
      output->SetDataSet(it, this->Leaves[index++].Output);
    }
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationBlockMerger::Deliver(vtkPolyData* lit, vtkDataObject* output)
{
  vtkPointData* results = lit->GetPointData();
  vtkPointData* merged = this->Merged->GetPointData();
  for (Leaf& leaf : this->Leaves)
  {
    const vtkIdType n = leaf.Input->GetNumberOfPoints();
    std::vector<vtkSmartPointer<vtkDataArray>> sources;
    vtkMTimeType time = 0;
    for (int a = 0; a < results->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* source = results->GetArray(a);
      if (source && source->GetName() && !merged->GetArray(source->GetName()) &&
        source->GetNumberOfTuples() >= leaf.FirstPoint + n)
      {
        sources.emplace_back(source);
        time = std::max(time, source->GetMTime());
      }
    }
    if (sources == leaf.Delivered && time == leaf.DeliveredTime)
    {
      continue; // the same results, unchanged: the leaf already has them
    }
    leaf.Output->ShallowCopy(leaf.Input); // drops the arrays of an earlier delivery
    for (vtkDataArray* source : sources)
    {
      if (leaf.FirstPoint == 0 && n == source->GetNumberOfTuples())
      {
        // The only leaf: its array is the result itself (each update makes new ones).
        leaf.Output->GetPointData()->AddArray(source);
        continue;
      }
      auto slice = vtk::TakeSmartPointer(source->NewInstance());
      slice->SetName(source->GetName());
      slice->SetNumberOfComponents(source->GetNumberOfComponents());
      slice->SetNumberOfTuples(n);
      slice->InsertTuples(0, n, leaf.FirstPoint, source);
      leaf.Output->GetPointData()->AddArray(slice);
    }
    leaf.Delivered = std::move(sources);
    leaf.DeliveredTime = time;
  }
  auto tree = vtkDataObjectTree::SafeDownCast(this->Structure);
  if (tree)
  {
    // The same leaf objects: a tree's ShallowCopy clones its leaves (VTK 9.2), and a mapper
    // takes a clone for new data, rebuilding all its buffers and bounds at every update.
    auto out = vtkDataObjectTree::SafeDownCast(output);
    out->CopyStructure(tree);
    out->GetFieldData()->ShallowCopy(tree->GetFieldData());
    auto it = vtk::TakeSmartPointer(tree->NewTreeIterator());
    it->VisitOnlyLeavesOn();
    it->SkipEmptyNodesOn();
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      out->SetDataSet(it, it->GetCurrentDataObject());
    }
  }
  else if (this->Structure)
  {
    output->ShallowCopy(this->Structure);
  }
  else
  {
    output->Initialize();
  }
  vtkFieldData* fieldData = lit->GetFieldData();
  for (int a = 0; a < fieldData->GetNumberOfArrays(); ++a)
  {
    output->GetFieldData()->AddArray(fieldData->GetAbstractArray(a));
  }
}
