// vtkGlobalIlluminationGlobalCasters under MPI (run with mpirun -np 3): every rank gets the
// triangles of the others and not its own, with their bounds; rank 2 has no data (null)
// and rank 1 a composite dataset. Repeated gathers and new point data exchange nothing;
// new points on one rank make every rank exchange again; past the least MaximumTriangles
// of the ranks every rank sends a decimated proxy (nothing at 0), all alike (no rank left
// waiting in the allgather).
#include "vtkGlobalIlluminationGlobalCasters.h"

#include "vtkFloatArray.h"
#include "vtkMPIController.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{
/// A triangulated unit square at height z, resolution n (2 n^2 triangles).
vtkSmartPointer<vtkPolyData> Square(double z, int n)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(0, 0, z);
  plane->SetPoint1(1, 0, z);
  plane->SetPoint2(0, 1, z);
  plane->SetResolution(n, n);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

bool Check(int rank, bool condition, const std::string& what)
{
  std::printf("rank %d: %s: %s\n", rank, condition ? "ok" : "FAILED", what.c_str());
  return condition;
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  bool ok = Check(rank, ranks == 3, "runs on 3 ranks");

  // Rank 0: a square at z = 0 (2 triangles); rank 1: two blocks of squares at z = 1 and 2
  // (8 + 18 triangles); rank 2: nothing.
  vtkSmartPointer<vtkDataObject> local;
  vtkSmartPointer<vtkPolyData> first;
  if (rank == 0)
  {
    first = Square(0.0, 1);
    local = first;
  }
  else if (rank == 1)
  {
    vtkNew<vtkMultiBlockDataSet> blocks;
    first = Square(1.0, 2);
    blocks->SetBlock(0, first);
    blocks->SetBlock(1, Square(2.0, 3));
    local = blocks;
  }
  const vtkIdType mine[3] = { 2, 26, 0 };
  const vtkIdType expected = 28 - mine[rank];

  vtkNew<vtkGlobalIlluminationGlobalCasters> casters;
  ok = Check(rank, casters->Gather(local), "the first gather exchanges") && ok;
  ok = Check(rank, casters->GetNumberOfTriangles() == expected,
         "holds the " + std::to_string(expected) + " triangles of the others (has " +
           std::to_string(casters->GetNumberOfTriangles()) + ")") &&
    ok;
  // The global bounds are [0,1] x [0,1] x [0,2]: the origin is their centre.
  const double* o = casters->GetOrigin();
  ok = Check(rank, o[0] == 0.5 && o[1] == 0.5 && o[2] == 1.0, "origin at the global centre") && ok;
  // The corners' heights: rank 0 sees 1 and 2, the others see 0 (and 1 or 2).
  const double* b = casters->GetBounds();
  const double zLow = rank == 0 ? 1.0 : 0.0, zHigh = rank == 1 ? 0.0 : 2.0;
  ok = Check(rank, b[4] == zLow && b[5] == zHigh && b[0] == 0.0 && b[1] == 1.0,
         "bounds of the others' triangles") &&
    ok;
  bool heights = true;
  for (std::size_t i = 2; i < casters->GetPositions().size(); i += 3)
  {
    const double z = o[2] + casters->GetPositions()[i];
    const bool own = rank == 0 ? std::round(z) == 0.0 : (rank == 1 && std::round(z) != 0.0);
    heights = heights && std::abs(z - std::round(z)) < 1e-6 && !own;
  }
  ok = Check(rank, heights, "no triangle of its own, all at the others' heights") && ok;
  ok = Check(rank, casters->GetLastGatherBytes() == 6 * 8 + expected * 36,
         "received 36 bytes per triangle plus the counts and limits") &&
    ok;

  ok = Check(rank, !casters->Gather(local), "a second gather exchanges nothing") && ok;
  if (first)
  {
    vtkNew<vtkFloatArray> irradiance;
    irradiance->SetName("IndirectIrradiance");
    irradiance->SetNumberOfComponents(3);
    irradiance->SetNumberOfTuples(first->GetNumberOfPoints());
    irradiance->Fill(1.0);
    first->GetPointData()->AddArray(irradiance);
    first->Modified();
  }
  ok = Check(rank, !casters->Gather(local), "new point data exchanges nothing") && ok;

  // Rank 0 lifts its square: every rank exchanges again.
  if (rank == 0)
  {
    first->GetPoints()->SetPoint(0, 0.0, 0.0, 0.5);
    first->GetPoints()->Modified();
  }
  ok = Check(rank, casters->Gather(local), "moved points on rank 0: every rank exchanges") && ok;
  ok = Check(rank, casters->GetNumberOfGathers() == 2, "two exchanges in all") && ok;

  // The limit: the least over the ranks counts, and all ranks act alike when any would
  // receive more (rank 2 lowers it to 10; rank 0 would receive 26, rank 2 28): each rank
  // sends a proxy of at most its share (10 / 2 = 5 triangles). Rank 0's 2 triangles go as
  // they are; rank 1's squares are clustered, and the proxies stay on their planes.
  if (rank == 0)
  {
    first->GetPoints()->SetPoint(0, 0.0, 0.0, 0.0); // flat again
    first->GetPoints()->Modified();
  }
  if (rank == 2)
  {
    casters->SetMaximumTriangles(10);
  }
  ok = Check(rank, casters->Gather(local), "a new limit on rank 2: every rank exchanges") && ok;
  ok = Check(rank, casters->GetOverLimit() && casters->GetProxies(),
         "every rank is over the least limit and exchanged proxies") &&
    ok;
  ok = Check(rank, casters->GetNumberOfTriangles() <= 10,
         "at most the limit received (" + std::to_string(casters->GetNumberOfTriangles()) + ")") &&
    ok;
  if (rank == 2)
  {
    ok = Check(rank, casters->GetNumberOfTriangles() >= 2, "rank 0's 2 triangles among them") && ok;
  }
  bool planar = true;
  for (std::size_t i = 2; i < casters->GetPositions().size(); i += 3)
  {
    const double z = o[2] + casters->GetPositions()[i];
    planar = planar && std::abs(z - std::round(z)) < 1e-5;
  }
  ok = Check(rank, planar, "the proxies lie on the squares' planes") && ok;
  casters->SetMaximumTriangles(0);
  ok = Check(rank, casters->Gather(local), "limit 0 everywhere: exchanges again") && ok;
  ok = Check(rank, casters->GetOverLimit() && !casters->GetProxies() &&
           casters->GetNumberOfTriangles() == 0,
         "at limit 0 nothing is kept, not even proxies") &&
    ok;
  casters->SetMaximumTriangles(28);
  ok = Check(rank, casters->Gather(local), "limit 28 everywhere: exchanges again") && ok;
  ok = Check(rank, !casters->GetOverLimit() && casters->GetNumberOfTriangles() == expected,
         "at the limit, all triangles are kept") &&
    ok;

  int failed = ok ? 0 : 1, anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  controller->Finalize();
  return anyFailed;
}
