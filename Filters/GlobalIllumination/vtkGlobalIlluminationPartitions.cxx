#include "vtkGlobalIlluminationPartitions.h"

#include "vtkAppendPolyData.h"
#include "vtkCommunicator.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedLongLongArray.h"

#include "linkgi/Error.h"

#include <array>
#include <cstring>
#include <map>
#include <string>

//------------------------------------------------------------------------------
vtkPolyData* vtkGlobalIlluminationPartitions::Gather(
  vtkMultiProcessController* controller, vtkPolyData* local)
{
  this->Processes = controller ? controller->GetNumberOfProcesses() : 1;
  this->Count = local->GetNumberOfPoints();
  this->Received = 0;
  *this->Exchanged = 0;
  if (this->Processes <= 1)
  {
    this->Global = nullptr;
    this->Offset = 0;
    this->Owners.clear();
    return local;
  }
  // Every process takes the same branch: the exchange is collective.
  const int changed = !this->Global || local != this->LocalInput || local->GetMTime() != this->LocalTime;
  int anyChanged = 0;
  controller->AllReduce(&changed, &anyChanged, 1, vtkCommunicator::MAX_OP);
  if (!anyChanged)
  {
    return this->Global;
  }

  // Ghost cells are another process's cells: sent by their owner only. Their points stay
  // (vtkPolyData::RemoveGhostCells would drop the unused ones, and the points' ghost flags),
  // so that this process's point ids are its points' places in the global surface.
  vtkSmartPointer<vtkPolyData> send = local;
  if (vtkUnsignedCharArray* cellGhosts = local->GetCellGhostArray())
  {
    send = vtkSmartPointer<vtkPolyData>::New();
    send->DeepCopy(local);
    send->BuildCells();
    for (vtkIdType c = 0; c < send->GetNumberOfCells(); ++c)
    {
      if (cellGhosts->GetValue(c) & (vtkDataSetAttributes::DUPLICATECELL | vtkDataSetAttributes::HIDDENCELL))
      {
        send->DeleteCell(c);
      }
    }
    send->RemoveDeletedCells();
  }
  std::vector<vtkSmartPointer<vtkDataObject>> all;
  if (!controller->AllGather(send, all) || int(all.size()) != this->Processes)
  {
    throw linkgi::Error("The exchange of the partitions' surfaces between the " +
      std::to_string(this->Processes) + " processes failed.");
  }
  vtkNew<vtkAppendPolyData> append;
  this->Offset = 0;
  const int me = controller->GetLocalProcessId();
  for (int p = 0; p < this->Processes; ++p)
  {
    vtkPolyData* part = vtkPolyData::SafeDownCast(all[p]);
    const vtkIdType points = part ? part->GetNumberOfPoints() : 0;
    if (p < me)
    {
      this->Offset += points;
    }
    if (p != me && part)
    {
      this->Received += std::size_t(part->GetActualMemorySize()) * 1024;
    }
    // An empty partition may lack the others' arrays, which vtkAppendPolyData would then
    // drop from the whole: it adds nothing anyway.
    if (points > 0)
    {
      append->AddInputData(part);
    }
  }
  this->Global = vtkSmartPointer<vtkPolyData>::New();
  if (append->GetNumberOfInputConnections(0) > 0)
  {
    append->Update();
    this->Global->ShallowCopy(append->GetOutput());
  }
  this->LocalInput = local;
  this->LocalTime = local->GetMTime();
  ++this->Generation;
  this->FindGhostOwners(local);
  return this->Global;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationPartitions::FindGhostOwners(vtkPolyData* local)
{
  this->Owners.clear();
  vtkUnsignedCharArray* ghosts = local->GetPointGhostArray();
  if (!ghosts)
  {
    return;
  }
  // The ghost points by their coordinates' bits: an owner's copy is the same point of the
  // same dataset, split, so its coordinates are equal.
  using Key = std::array<double, 3>;
  std::map<Key, vtkIdType> wanted;
  for (vtkIdType i = 0; i < this->Count; ++i)
  {
    if (ghosts->GetValue(i) & vtkDataSetAttributes::DUPLICATEPOINT)
    {
      Key k;
      local->GetPoint(i, k.data());
      wanted.emplace(k, i);
    }
  }
  if (wanted.empty() || !this->Global)
  {
    return;
  }
  // Another process's copy that is not a ghost there (any copy where the parts carry no
  // ghost flags), the first in process order.
  vtkUnsignedCharArray* globalGhosts = this->Global->GetPointGhostArray();
  const vtkIdType n = this->Global->GetNumberOfPoints();
  for (vtkIdType g = 0; g < n && !wanted.empty(); ++g)
  {
    if ((g >= this->Offset && g < this->Offset + this->Count) ||
      (globalGhosts && (globalGhosts->GetValue(g) & vtkDataSetAttributes::DUPLICATEPOINT)))
    {
      continue;
    }
    Key k;
    this->Global->GetPoint(g, k.data());
    const auto found = wanted.find(k);
    if (found != wanted.end())
    {
      this->Owners.emplace_back(found->second, g);
      wanted.erase(found);
    }
  }
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationPartitions::Scatter(vtkPolyData* lit, vtkPolyData* local, vtkPolyData* output) const
{
  output->ShallowCopy(local);
  vtkPointData* from = lit->GetPointData();
  vtkPointData* to = output->GetPointData();
  for (int i = 0; i < from->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* source = from->GetAbstractArray(i);
    if (!source->GetName() || local->GetPointData()->HasArray(source->GetName()))
    {
      continue; // the input's own arrays are those of `local` already
    }
    vtkSmartPointer<vtkAbstractArray> mine = vtk::TakeSmartPointer(source->NewInstance());
    mine->SetName(source->GetName());
    mine->SetNumberOfComponents(source->GetNumberOfComponents());
    mine->SetNumberOfTuples(this->Count);
    if (this->Count > 0)
    {
      mine->InsertTuples(0, this->Count, this->Offset, source);
    }
    for (const auto& owner : this->Owners)
    {
      mine->SetTuple(owner.first, owner.second, source);
    }
    to->AddArray(mine);
  }
  // The results' field data (counters, timings, warnings), and where this process's part is.
  vtkFieldData* fields = output->GetFieldData();
  vtkNew<vtkFieldData> merged;
  merged->ShallowCopy(fields);
  for (int i = 0; i < lit->GetFieldData()->GetNumberOfArrays(); ++i)
  {
    merged->AddArray(lit->GetFieldData()->GetAbstractArray(i));
  }
  vtkNew<vtkIntArray> processes;
  processes->SetName("LinkGI.Processes");
  processes->InsertNextValue(this->Processes);
  merged->AddArray(processes);
  vtkNew<vtkUnsignedLongLongArray> received;
  received->SetName("LinkGI.PartitionBytesReceived");
  received->InsertNextValue(this->Received);
  merged->AddArray(received);
  vtkNew<vtkUnsignedLongLongArray> exchanged;
  exchanged->SetName("LinkGI.RadianceBytesExchanged");
  exchanged->InsertNextValue(*this->Exchanged);
  merged->AddArray(exchanged);
  output->SetFieldData(merged);
}

//------------------------------------------------------------------------------
std::shared_ptr<const linkgi::Partition> vtkGlobalIlluminationPartitions::Rows(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& elementPoint, bool twoSided)
{
  if (!this->Distributed())
  {
    this->Partition.reset();
    return nullptr;
  }
  const std::size_t elements = elementPoint.size() * (twoSided ? 2 : 1);
  if (this->Partition && this->PartitionGeneration == this->Generation && this->PartitionElements == elements)
  {
    return this->Partition;
  }
  std::vector<std::uint8_t> rows(elements);
  for (std::size_t e = 0; e < elements; ++e)
  {
    const vtkIdType point = elementPoint[e % elementPoint.size()];
    rows[e] = point >= this->Offset && point < this->Offset + this->Count ? 1 : 0;
  }
  this->PartitionGeneration = this->Generation;
  if (this->Partition && this->Partition->rows == rows)
  {
    return this->Partition; // the surfaces were exchanged again, but the rows are the same
  }
  auto partition = std::make_shared<linkgi::Partition>(Collectives(controller));
  partition->rows = std::move(rows);
  std::shared_ptr<std::uint64_t> exchanged = this->Exchanged;
  partition->sum = [controller, exchanged](std::vector<linkgi::Vec3f>& values) {
    const vtkIdType n = static_cast<vtkIdType>(3 * values.size());
    std::vector<float> sum(values.size() * 3);
    controller->AllReduce(reinterpret_cast<const float*>(values.data()), sum.data(), n, vtkCommunicator::SUM_OP);
    std::memcpy(values.data(), sum.data(), sizeof(float) * sum.size());
    *exchanged += sizeof(float) * sum.size();
  };
  this->Partition = partition;
  this->PartitionElements = elements;
  return this->Partition;
}

//------------------------------------------------------------------------------
void vtkGlobalIlluminationPartitions::Together(
  vtkMultiProcessController* controller, const std::function<void()>& work) const
{
  if (!this->Distributed())
  {
    work();
    return;
  }
  const linkgi::Partition collectives = Collectives(controller);
  linkgi::together(&collectives, work);
}

//------------------------------------------------------------------------------
linkgi::Partition vtkGlobalIlluminationPartitions::Collectives(vtkMultiProcessController* controller)
{
  linkgi::Partition p;
  p.least = [controller](std::uint64_t value) {
    vtkTypeUInt64 mine = value, least = value;
    controller->AllReduce(&mine, &least, 1, vtkCommunicator::MIN_OP);
    return static_cast<std::uint64_t>(least);
  };
  p.count = [controller](std::uint64_t value) {
    vtkTypeUInt64 mine = value, total = value;
    controller->AllReduce(&mine, &total, 1, vtkCommunicator::SUM_OP);
    return static_cast<std::uint64_t>(total);
  };
  return p;
}
