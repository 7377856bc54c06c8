#include "vtkGlobalIlluminationGlobalCasters.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkQuadricClustering.h"
#include "vtkUnsignedCharArray.h"

#if VTK_MODULE_ENABLE_VTK_ParallelCore
#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#endif

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

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

#if VTK_MODULE_ENABLE_VTK_ParallelCore
/// What every process sends, learnt by all: the lengths (floats), their total, the least
/// limit (triangles) and whether some process would receive more than that.
struct Sizes
{
  std::vector<vtkIdType> Lengths;
  vtkIdType Total = 0;
  vtkIdType Limit = VTK_ID_MAX;
  bool Over = false;
  vtkIdType Bytes = 0; // received by this exchange
  std::string LimitReason;
};

Sizes ExchangeSizes(vtkMultiProcessController* controller, vtkIdType length, vtkIdType maximum)
{
  const int processes = controller->GetNumberOfProcesses();
  const vtkIdType mine[2] = { length, maximum };
  std::vector<vtkIdType> all(2 * processes, 0);
  controller->AllGather(mine, all.data(), 2);
  Sizes sizes;
  sizes.Lengths.resize(processes);
  for (int p = 0; p < processes; ++p)
  {
    sizes.Lengths[p] = all[2 * p];
    sizes.Total += all[2 * p];
    sizes.Limit = std::min(sizes.Limit, all[2 * p + 1]);
  }
  vtkIdType most = 0; // the most triangles any process would receive
  for (int p = 0; p < processes; ++p)
  {
    most = std::max(most, (sizes.Total - sizes.Lengths[p]) / 9);
  }
  // MPI counts are ints.
  sizes.Over = sizes.Total > std::numeric_limits<int>::max() || most > sizes.Limit;
  sizes.Bytes = static_cast<vtkIdType>(all.size() * sizeof(vtkIdType));
  sizes.LimitReason = std::to_string(most) + " for the process that has the fewest itself";
  return sizes;
}

/// At most `triangles` triangles (9 floats each, relative to `origin`) that approximate
/// the triangles of `leaves`: vertex clustering (vtkQuadricClustering) of their shared
/// points on a grid of cubic bins, coarsened until they fit. The grid has at most 128 bins
/// along its longest side (the clustering holds a quadric per bin: 170 MB at most).
std::vector<float> Decimate(
  const std::vector<vtkPolyData*>& leaves, const double origin[3], vtkIdType triangles)
{
  // The surfaces alone: the clustering would carry point data along. (Ghost cells are
  // clustered too: a neighbour's copy of them only shadows what they shadow anyway.)
  vtkNew<vtkAppendPolyData> append;
  for (vtkPolyData* leaf : leaves)
  {
    if (leaf->GetNumberOfPoints() == 0)
    {
      continue;
    }
    vtkNew<vtkPolyData> geometry;
    geometry->SetPoints(leaf->GetPoints());
    geometry->SetPolys(leaf->GetPolys());
    geometry->SetStrips(leaf->GetStrips());
    append->AddInputData(geometry);
  }
  append->Update();
  vtkPolyData* surfaces = append->GetOutput();
  double bounds[6];
  surfaces->GetBounds(bounds);
  const double size =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-30 });
  // A surface crosses about (bins along a side)^2 bins, two triangles each.
  double side = std::min(128.0, std::sqrt(std::max(1.0, 0.5 * double(triangles))));
  std::vector<float> out;
  for (;;)
  {
    vtkNew<vtkQuadricClustering> clustering;
    clustering->SetInputData(surfaces);
    clustering->AutoAdjustNumberOfDivisionsOff();
    int divisions[3];
    for (int k = 0; k < 3; ++k)
    {
      const double extent = bounds[2 * k + 1] - bounds[2 * k];
      divisions[k] = std::max(1, static_cast<int>(std::ceil(side * extent / size)));
    }
    clustering->SetNumberOfDivisions(divisions);
    clustering->Update();
    vtkPolyData* proxy = clustering->GetOutput();
    const vtkIdType made = proxy->GetNumberOfPolys();
    if (made <= triangles || side <= 1.0)
    {
      out.clear();
      if (made <= triangles)
      {
        AppendTriangles(proxy, origin, out);
      }
      return out;
    }
    const double shrink = std::min(0.9, 0.95 * std::sqrt(double(triangles) / made));
    side = std::max(1.0, std::floor(side * shrink));
  }
}

/// The centre of the bounds of every process's `leaves`: the common origin of the positions.
void GlobalCentre(
  vtkMultiProcessController* controller, const std::vector<vtkPolyData*>& leaves, double centre[3])
{
  // min and -max, reduced together
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
    centre[k] = empty ? 0.0 : 0.5 * (global[k] - global[3 + k]);
  }
}

/// The triangles of `leaves`, 9 floats each, relative to `origin`.
std::vector<float> OwnTriangles(const std::vector<vtkPolyData*>& leaves, const double origin[3])
{
  vtkIdType corners = 0; // at most 3 (n - 2) per cell of n points
  for (vtkPolyData* poly : leaves)
  {
    corners += 3 * (poly->GetPolys()->GetNumberOfConnectivityIds() +
                     poly->GetStrips()->GetNumberOfConnectivityIds());
  }
  std::vector<float> triangles;
  triangles.reserve(static_cast<std::size_t>(3 * corners));
  for (vtkPolyData* poly : leaves)
  {
    AppendTriangles(poly, origin, triangles);
  }
  return triangles;
}
#endif

/// The bounds of `positions` (xyz relative to `origin`); empty (min > max) without any.
void BoundsOf(const std::vector<float>& positions, const double origin[3], double bounds[6])
{
  for (int k = 0; k < 3; ++k)
  {
    bounds[2 * k] = positions.empty() ? 1.0 : VTK_DOUBLE_MAX;
    bounds[2 * k + 1] = positions.empty() ? -1.0 : -VTK_DOUBLE_MAX;
  }
  for (std::size_t i = 0; i < positions.size(); i += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double x = origin[k] + positions[i + k];
      bounds[2 * k] = std::min(bounds[2 * k], x);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], x);
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

  GlobalCentre(controller, leaves, this->Origin);
  std::vector<float> mine = OwnTriangles(leaves, this->Origin);
  // Every process learns every length and limit, so all decide alike (a process that
  // gave up alone would leave the others in the allgather).
  Sizes sizes = ExchangeSizes(controller, static_cast<vtkIdType>(mine.size()), this->MaximumTriangles);
  this->LastGatherBytes = sizes.Bytes;
  const vtkIdType fullTriangles = (sizes.Total - static_cast<vtkIdType>(mine.size())) / 9;
  const std::string fullReason = sizes.LimitReason;
  const bool overLimit = sizes.Over;
  if (overLimit && sizes.Limit > 0)
  {
    // Decimated proxies that fit: each process sends at most its share of the limit.
    const vtkIdType share = sizes.Limit / (processes - 1);
    if (static_cast<vtkIdType>(mine.size() / 9) > share)
    {
      mine = Decimate(leaves, this->Origin, share);
    }
    sizes = ExchangeSizes(controller, static_cast<vtkIdType>(mine.size()), this->MaximumTriangles);
    this->LastGatherBytes += sizes.Bytes;
  }
  ++this->NumberOfGathers;
  this->Positions.clear();
  BoundsOf(this->Positions, this->Origin, this->Bounds);
  this->Proxies = overLimit && !sizes.Over;
  if (overLimit && (!this->OverLimit || this->Proxies != this->WarnedProxies))
  {
    vtkWarningMacro(<< "The other processes hold " << fullTriangles << " triangles ("
                    << fullReason << "), more than MaximumTriangles (" << sizes.Limit
                    << ", the least over the processes): "
                    << (this->Proxies
                           ? "their shadows come from decimated proxies (approximate)."
                           : "their shadows are missing from the shadow maps."));
    this->WarnedProxies = this->Proxies;
  }
  this->OverLimit = overLimit;
  if (sizes.Over)
  {
    this->Modified();
    return true;
  }
  std::vector<vtkIdType> lengths = sizes.Lengths;
  const vtkIdType myLength = static_cast<vtkIdType>(mine.size());
  const vtkIdType total = sizes.Total, others = total - myLength;
  std::vector<vtkIdType> offsets(processes, 0);
  for (int p = 1; p < processes; ++p)
  {
    offsets[p] = offsets[p - 1] + lengths[p - 1];
  }
  // Received in place; this process's own segment is then cut out (one move of the rest).
  this->Positions.resize(static_cast<std::size_t>(total));
  controller->AllGatherV(
    mine.data(), this->Positions.data(), myLength, lengths.data(), offsets.data());
  this->LastGatherBytes += static_cast<vtkIdType>(others * sizeof(float));
  const auto own = this->Positions.begin() + offsets[controller->GetLocalProcessId()];
  this->Positions.erase(own, own + myLength);
  BoundsOf(this->Positions, this->Origin, this->Bounds);
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
