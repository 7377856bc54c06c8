// The filter under MPI: every process holds a partition of the surface, and the
// light crosses partition boundaries (a shadow cast by one process's geometry onto
// another's, light bounced between them). Gather() appends every process's surface, in
// process order, into one global surface that each process lights; Scatter() hands each
// process the light of its own points. Private to the module.
#ifndef vtkGlobalIlluminationPartitions_h
#define vtkGlobalIlluminationPartitions_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "linkgi/SolverTypes.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkMultiProcessController;

class vtkGlobalIlluminationPartitions
{
public:
  /// The surface to light: `local` itself without a controller or with one process, else
  /// the global surface (every process's surface without its ghost cells, appended in
  /// process order). Collective: every process of `controller` must call it, those without
  /// data with an empty surface. The global surface is exchanged again only when some
  /// process's surface changed (one reduction per call otherwise), so a light move costs no
  /// exchange and keeps the engine's links.
  vtkPolyData* Gather(vtkMultiProcessController* controller, vtkPolyData* local);

  /// Whether the last Gather lit a global surface of more than one process.
  bool Distributed() const { return this->Processes > 1; }
  int ProcessCount() const { return this->Processes; }
  /// This process's points in the global surface: [Offset, Offset + Count).
  vtkIdType PointOffset() const { return this->Offset; }
  /// Bytes this process received in the last exchange (0 when nothing was exchanged).
  std::size_t ReceivedBytes() const { return this->Received; }

  /// The engine's partition for the last Gather: this process's rows are the elements of its
  /// own points (`elementPoint`: each element's point in the global surface; the back sides
  /// of a two-sided solve follow the fronts), the exchange an allreduce of the sum through
  /// `controller`. The same object until the global surface or this process's part changes
  /// (another object would make the engine relink). Null with one process.
  std::shared_ptr<const linkgi::Partition> Rows(vtkMultiProcessController* controller,
    const std::vector<vtkIdType>& elementPoint, bool twoSided);

  /// Runs `work`, this process's part of an update of the last Gather's surface. Collective
  /// when the surface is distributed (linkgi::together): when `work` throws on any process,
  /// it throws on all - the error itself where it happened, linkgi::PeerFailed on the others
  /// - so all keep their previous result and none waits in an exchange for one that left.
  void Together(vtkMultiProcessController* controller, const std::function<void()>& work) const;

  /// `output` = `local` with every point array of `lit` (the lit global surface) that
  /// `local` lacks, cut to this process's points, and `lit`'s field data, with
  /// LinkGI.Processes, LinkGI.PartitionBytesReceived and LinkGI.RadianceBytesExchanged (what
  /// the bounces' exchanges moved into this process in the last update). Ghost points
  /// (vtkGhostType's DUPLICATEPOINT) take the values of their owner's copy: the point at the
  /// same place in another process's part that is not a ghost there.
  void Scatter(vtkPolyData* lit, vtkPolyData* local, vtkPolyData* output) const;

  /// For each of this process's ghost points whose owner's copy was found: (its id here, the
  /// copy's id in the global surface). Set by Gather.
  const std::vector<std::pair<vtkIdType, vtkIdType>>& GhostOwners() const { return this->Owners; }

private:
  void FindGhostOwners(vtkPolyData* local);
  /// A linkgi::Partition without rows: the collectives over `controller`.
  static linkgi::Partition Collectives(vtkMultiProcessController* controller);

  vtkSmartPointer<vtkPolyData> Global;
  std::vector<std::pair<vtkIdType, vtkIdType>> Owners;
  const vtkPolyData* LocalInput = nullptr;
  vtkMTimeType LocalTime = 0;
  int Processes = 1;
  vtkIdType Offset = 0;
  vtkIdType Count = 0;
  std::size_t Received = 0;
  std::shared_ptr<linkgi::Partition> Partition;
  /// Counts the exchanges that replaced Global; the partition follows it (not Global's
  /// MTime, which the steps after Gather may touch without changing the surface).
  std::uint64_t Generation = 0, PartitionGeneration = 0;
  std::size_t PartitionElements = 0;
  /// Bytes each process sent and received through the partition's exchanges since the last
  /// Gather (shared with the exchange, which counts them).
  std::shared_ptr<std::uint64_t> Exchanged = std::make_shared<std::uint64_t>(0);
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationPartitions.h
