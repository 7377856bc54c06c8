// vtkGlobalIlluminationSceneBuilder's canonical order of cells: the same surface makes the
// same scene whatever order its cells come in.
#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace
{
// A vtkCellArray's offsets and point ids, whatever its storage.
struct CopyCells
{
  template <typename State>
  void operator()(State& state, std::vector<vtkIdType>& offsets, std::vector<vtkIdType>& ids) const
  {
    auto* o = state.GetOffsets();
    auto* c = state.GetConnectivity();
    offsets.assign(o->GetPointer(0), o->GetPointer(0) + o->GetNumberOfValues());
    ids.assign(c->GetPointer(0), c->GetPointer(0) + c->GetNumberOfValues());
  }
};

// A cell's place in the canonical order: its three lowest point ids decide almost always,
// and do not depend on where the cell's list starts or which way it winds.
struct CellKey
{
  std::array<vtkIdType, 3> Lowest; // ascending; -1 where the cell has fewer points
  vtkIdType Cell;
};

// Ties of CellKey::Lowest (the same cell twice, or polygons sharing their three lowest
// points): all point ids ascending, then as listed, then the place in the input.
bool TieBefore(const std::vector<vtkIdType>& offsets, const std::vector<vtkIdType>& ids,
  vtkIdType a, vtkIdType b)
{
  const auto list = [&](vtkIdType c) {
    return std::vector<vtkIdType>(ids.begin() + offsets[c], ids.begin() + offsets[c + 1]);
  };
  std::vector<vtkIdType> la = list(a), lb = list(b), sa = la, sb = lb;
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  return sa != sb ? sa < sb : la != lb ? la < lb : a < b;
}

}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkCellArray> vtkGlobalIlluminationSceneBuilder::CanonicalCells(
  vtkCellArray* cells, vtkIdType minimumSize, std::vector<vtkIdType>& index)
{
  std::vector<vtkIdType> offsets, points;
  cells->Visit(CopyCells{}, offsets, points);
  std::vector<CellKey> keys;
  keys.reserve(offsets.size());
  for (vtkIdType c = 0; c + 1 < static_cast<vtkIdType>(offsets.size()); ++c)
  {
    const auto first = points.begin() + offsets[c], last = points.begin() + offsets[c + 1];
    if (last - first >= minimumSize)
    {
      CellKey key{ { -1, -1, -1 }, c };
      const auto lowest = std::min<std::ptrdiff_t>(3, last - first);
      std::partial_sort_copy(first, last, key.Lowest.begin(), key.Lowest.begin() + lowest);
      keys.push_back(key);
    }
  }
  const auto before = [&](const CellKey& a, const CellKey& b) {
    return a.Lowest != b.Lowest ? a.Lowest < b.Lowest : TieBefore(offsets, points, a.Cell, b.Cell);
  };
  index.resize(keys.size());
  if (keys.size() + 1 == offsets.size() && std::is_sorted(keys.begin(), keys.end(), before))
  {
    std::iota(index.begin(), index.end(), vtkIdType(0));
    return cells; // already in that order: no copy
  }
  vtkSMPTools::Sort(keys.begin(), keys.end(), before);

  vtkNew<vtkIdTypeArray> sortedOffsets, sortedPoints;
  sortedOffsets->SetNumberOfValues(static_cast<vtkIdType>(keys.size()) + 1);
  sortedPoints->SetNumberOfValues(static_cast<vtkIdType>(points.size()));
  vtkIdType next = 0;
  sortedOffsets->SetValue(0, 0);
  for (std::size_t k = 0; k < keys.size(); ++k)
  {
    const vtkIdType c = keys[k].Cell;
    for (vtkIdType p = offsets[c]; p < offsets[c + 1]; ++p)
    {
      sortedPoints->SetValue(next++, points[static_cast<std::size_t>(p)]);
    }
    sortedOffsets->SetValue(static_cast<vtkIdType>(k) + 1, next);
    index[k] = c;
  }
  sortedPoints->SetNumberOfValues(next); // strips of fewer than minimumSize points left out
  auto sorted = vtkSmartPointer<vtkCellArray>::New();
  sorted->SetData(sortedOffsets, sortedPoints);
  return sorted;
}
