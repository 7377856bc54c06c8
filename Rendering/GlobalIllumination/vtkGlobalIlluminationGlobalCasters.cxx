#include "vtkGlobalIlluminationGlobalCasters.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#if VTK_MODULE_ENABLE_VTK_ParallelCore
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#endif

#include <algorithm>
#include <cstdint>
#include <limits>

vtkStandardNewMacro(vtkGlobalIlluminationGlobalCasters);

namespace
{
/// The polydata leaves of `data` (itself, if it is one).
std::vector<vtkPolyData*> Leaves(vtkDataObject* data)
{
  std::vector<vtkPolyData*> leaves;
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    leaves.push_back(poly);
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    for (vtkPolyData* leaf : vtkCompositeDataSet::GetDataSets<vtkPolyData>(composite))
    {
      leaves.push_back(leaf);
    }
  }
  return leaves;
}

/// What the triangles of `leaves` depend on: the objects holding the points and cells, and
/// their modification times (not the point data's).
std::vector<double> GeometrySignature(const std::vector<vtkPolyData*>& leaves)
{
  std::vector<double> s;
  const auto add = [&s](vtkObject* o)
  {
    s.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(o)));
    s.push_back(o ? static_cast<double>(o->GetMTime()) : 0.0);
  };
  for (vtkPolyData* poly : leaves)
  {
    vtkPoints* points = poly->GetPoints();
    add(points);
    add(points ? points->GetData() : nullptr);
    add(poly->GetPolys());
    add(poly->GetStrips());
    add(poly->GetVerts());
    add(poly->GetLines());
    add(poly->GetCellGhostArray());
  }
  return s;
}

/// Appends the triangles of `poly` (fanned polygons, split strips, no duplicate cells) as
/// corner positions relative to `origin`.
void AppendTriangles(vtkPolyData* poly, const double origin[3], std::vector<float>& out)
{
  vtkPoints* points = poly->GetPoints();
  if (!points)
  {
    return;
  }
  vtkUnsignedCharArray* ghosts = poly->GetCellGhostArray();
  vtkIdType cellId = poly->GetNumberOfVerts() + poly->GetNumberOfLines();
  double p[3];
  const auto corner = [&](vtkIdType id)
  {
    points->GetPoint(id, p);
    for (int k = 0; k < 3; ++k)
    {
      out.push_back(static_cast<float>(p[k] - origin[k]));
    }
  };
  for (int strips = 0; strips < 2; ++strips)
  {
    vtkCellArray* cells = strips ? poly->GetStrips() : poly->GetPolys();
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      if (ghosts && (ghosts->GetValue(cellId) & vtkDataSetAttributes::DUPLICATECELL))
      {
        continue;
      }
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 2; k < n; ++k)
      {
        if (strips)
        {
          // Alternate the winding like a strip does (shadows do not need it; tidy anyway).
          const bool odd = (k % 2) == 1;
          corner(ids[k - 2]);
          corner(ids[odd ? k : k - 1]);
          corner(ids[odd ? k - 1 : k]);
        }
        else
        {
          corner(ids[0]);
          corner(ids[k - 1]);
          corner(ids[k]);
        }
      }
    }
  }
}
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationGlobalCasters::vtkGlobalIlluminationGlobalCasters() = default;

//------------------------------------------------------------------------------
vtkGlobalIlluminationGlobalCasters::~vtkGlobalIlluminationGlobalCasters() = default;

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationGlobalCasters::IsParallel()
{
#if VTK_MODULE_ENABLE_VTK_ParallelCore
  return true;
#else
  return false;
#endif
}

//------------------------------------------------------------------------------
bool vtkGlobalIlluminationGlobalCasters::Gather(vtkDataObject* local)
{
#if VTK_MODULE_ENABLE_VTK_ParallelCore
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  this->NumberOfProcesses = processes;
  if (processes <= 1)
  {
    const bool had = !this->Positions.empty();
    this->Positions.clear();
    this->Gathered = false;
    return had;
  }
  const std::vector<vtkPolyData*> leaves = Leaves(local);
  std::vector<double> signature = GeometrySignature(leaves);
  int changed = (!this->Gathered || signature != this->Signature ||
                  this->GatheredMaximum != this->MaximumTriangles)
    ? 1
    : 0;
  int anyChanged = 0;
  controller->AllReduce(&changed, &anyChanged, 1, vtkCommunicator::MAX_OP);
  if (!anyChanged)
  {
    return false;
  }
  this->Signature = std::move(signature);
  this->Gathered = true;
  this->GatheredMaximum = this->MaximumTriangles;

  // A common origin: the centre of the global bounds (min and -max reduced together).
  double bounds[6] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  for (vtkPolyData* poly : leaves)
  {
    if (poly->GetNumberOfPoints() == 0)
    {
      continue;
    }
    double b[6];
    poly->GetBounds(b);
    for (int k = 0; k < 3; ++k)
    {
      bounds[k] = std::min(bounds[k], b[2 * k]);
      bounds[3 + k] = std::min(bounds[3 + k], -b[2 * k + 1]);
    }
  }
  double global[6];
  controller->AllReduce(bounds, global, 6, vtkCommunicator::MIN_OP);
  const bool empty = global[0] > -global[3];
  for (int k = 0; k < 3; ++k)
  {
    this->Origin[k] = empty ? 0.0 : 0.5 * (global[k] - global[3 + k]);
  }

  std::vector<float> mine;
  for (vtkPolyData* poly : leaves)
  {
    AppendTriangles(poly, this->Origin, mine);
  }
  // Every process learns every length and limit, so all decide alike (a process that
  // gave up alone would leave the others in the allgather).
  const vtkIdType myLength = static_cast<vtkIdType>(mine.size());
  const vtkIdType mySizes[2] = { myLength, this->MaximumTriangles };
  std::vector<vtkIdType> sizes(2 * processes, 0);
  controller->AllGather(mySizes, sizes.data(), 2);
  std::vector<vtkIdType> lengths(processes, 0);
  vtkIdType total = 0, limit = VTK_ID_MAX;
  for (int p = 0; p < processes; ++p)
  {
    lengths[p] = sizes[2 * p];
    total += lengths[p];
    limit = std::min(limit, sizes[2 * p + 1]);
  }
  vtkIdType mostOthers = 0; // the most triangles any process would receive
  for (int p = 0; p < processes; ++p)
  {
    mostOthers = std::max(mostOthers, (total - lengths[p]) / 9);
  }
  const vtkIdType others = total - myLength;
  const vtkIdType otherTriangles = others / 9;
  // MPI counts are ints.
  const bool overLimit = total > std::numeric_limits<int>::max() || mostOthers > limit;
  ++this->NumberOfGathers;
  this->Positions.clear();
  this->LastGatherBytes = static_cast<vtkIdType>(sizes.size() * sizeof(vtkIdType));
  for (int k = 0; k < 6; ++k)
  {
    this->Bounds[k] = (k % 2) ? -1.0 : 1.0; // empty
  }
  if (overLimit)
  {
    if (!this->OverLimit)
    {
      vtkWarningMacro(<< "The other processes hold " << otherTriangles << " triangles ("
                      << mostOthers << " for the process that has the fewest itself), more than "
                      << "MaximumTriangles (" << limit << ", the least over the processes): "
                      << "their shadows are missing from the shadow maps.");
    }
    this->OverLimit = true;
    this->Modified();
    return true;
  }
  this->OverLimit = false;
  std::vector<vtkIdType> offsets(processes, 0);
  for (int p = 1; p < processes; ++p)
  {
    offsets[p] = offsets[p - 1] + lengths[p - 1];
  }
  std::vector<float> all(static_cast<std::size_t>(total));
  controller->AllGatherV(mine.data(), all.data(), myLength, lengths.data(), offsets.data());
  this->LastGatherBytes += static_cast<vtkIdType>(others * sizeof(float));
  const int me = controller->GetLocalProcessId();
  this->Positions.reserve(static_cast<std::size_t>(others));
  this->Positions.insert(this->Positions.end(), all.begin(), all.begin() + offsets[me]);
  this->Positions.insert(this->Positions.end(), all.begin() + offsets[me] + myLength, all.end());
  for (int k = 0; k < 3; ++k)
  {
    this->Bounds[2 * k] = VTK_DOUBLE_MAX;
    this->Bounds[2 * k + 1] = -VTK_DOUBLE_MAX;
  }
  for (std::size_t i = 0; i < this->Positions.size(); i += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double x = this->Origin[k] + this->Positions[i + k];
      this->Bounds[2 * k] = std::min(this->Bounds[2 * k], x);
      this->Bounds[2 * k + 1] = std::max(this->Bounds[2 * k + 1], x);
    }
  }
  if (this->Positions.empty())
  {
    for (int k = 0; k < 6; ++k)
    {
      this->Bounds[k] = (k % 2) ? -1.0 : 1.0;
    }
  }
  this->Modified();
  return true;
#else
  (void)local;
  this->NumberOfProcesses = 1;
  return false;
#endif
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationGlobalCasters::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumTriangles: " << this->MaximumTriangles << "\n";
  os << indent << "NumberOfProcesses: " << this->NumberOfProcesses << "\n";
  os << indent << "NumberOfTriangles: " << this->GetNumberOfTriangles() << "\n";
  os << indent << "NumberOfGathers: " << this->NumberOfGathers << "\n";
  os << indent << "OverLimit: " << this->OverLimit << "\n";
}
