// vtkGlobalIlluminationFilter under MPI (run with mpirun -np 2 or 3): rank 0 holds a block,
// rank 1 the floor under it, rank 2 (if any) nothing. Each rank lights its partition with
// the light of all of them: its arrays equal, point for point, those of one process lighting
// the appended surface (block, then floor); the block's shadow falls on rank 1's floor, which
// a rank lighting its partition alone does not see; a light move exchanges nothing and re-runs
// only the light links and the bounces. Instant radiosity, photon mapping and implicit
// visibility gather by rows too. Then the floor
// split between ranks 0 and 1 with a layer of ghost cells each: the ghost points get their
// owner's values. Memory budgets that differ between the ranks: all take the smallest.
#include "vtkGlobalIlluminationFilter.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkLight.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> Triangulated(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

/// A 0.4-wide block standing on the floor's centre.
vtkSmartPointer<vtkPolyData> Block()
{
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-0.2, 0.2, -0.2, 0.2, 0.0, 0.4);
  return Triangulated(cube);
}

/// The floor: 2 x 2 at z = 0, 24 x 24 quads.
vtkSmartPointer<vtkPolyData> Floor()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1, -1, 0);
  plane->SetPoint1(1, -1, 0);
  plane->SetPoint2(-1, 1, 0);
  plane->SetResolution(24, 24);
  return Triangulated(plane);
}

bool Check(int rank, bool condition, const std::string& what)
{
  std::printf("rank %d: %s: %s\n", rank, condition ? "ok" : "FAILED", what.c_str());
  std::fflush(stdout);
  return condition;
}

double Field(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = vtkDataArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(name));
  return a ? a->GetTuple1(0) : -1.0;
}

void Configure(vtkGlobalIlluminationFilter* filter, vtkLight* light)
{
  filter->SetRaysPerVertex(64);
  filter->SetNumberOfBounces(2);
  filter->AddLight(light);
}

/// Rank `rank`'s half of `floor` (cells left of x = 0 for rank 0, right of it for rank 1),
/// with the other half's cells within `layer` of x = 0 as ghost cells (DUPLICATECELL); points
/// that only ghost cells use are ghost points (DUPLICATEPOINT). Other ranks get nothing.
vtkSmartPointer<vtkPolyData> Half(vtkPolyData* floor, int rank, double layer)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  if (rank > 1)
  {
    return out;
  }
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> cellGhosts, pointGhosts;
  cellGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
  pointGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
  std::map<vtkIdType, vtkIdType> ids; // floor point -> this half's point
  std::vector<bool> owned;
  for (vtkIdType c = 0; c < floor->GetNumberOfCells(); ++c)
  {
    vtkCell* cell = floor->GetCell(c);
    double centre = 0.0;
    for (vtkIdType k = 0; k < 3; ++k)
    {
      centre += floor->GetPoint(cell->GetPointId(k))[0] / 3.0;
    }
    const bool mine = rank == 0 ? centre < 0.0 : centre > 0.0;
    if (!mine && std::abs(centre) > layer)
    {
      continue;
    }
    vtkIdType corners[3];
    for (vtkIdType k = 0; k < 3; ++k)
    {
      const vtkIdType p = cell->GetPointId(k);
      auto found = ids.find(p);
      if (found == ids.end())
      {
        found = ids.emplace(p, points->InsertNextPoint(floor->GetPoint(p))).first;
        owned.push_back(false);
      }
      corners[k] = found->second;
      if (mine)
      {
        owned[corners[k]] = true;
      }
    }
    polys->InsertNextCell(3, corners);
    cellGhosts->InsertNextValue(mine ? 0 : vtkDataSetAttributes::DUPLICATECELL);
  }
  for (const bool o : owned)
  {
    pointGhosts->InsertNextValue(o ? 0 : vtkDataSetAttributes::DUPLICATEPOINT);
  }
  out->SetPoints(points);
  out->SetPolys(polys);
  out->GetCellData()->AddArray(cellGhosts);
  out->GetPointData()->AddArray(pointGhosts);
  return out;
}

/// Largest relative difference of `name` between `mine` and `reference`'s points from `offset`.
double Difference(vtkPolyData* mine, vtkPolyData* reference, vtkIdType offset, const char* name)
{
  vtkDataArray* a = mine->GetPointData()->GetArray(name);
  vtkDataArray* b = reference->GetPointData()->GetArray(name);
  if (!a || !b)
  {
    return 1e30;
  }
  double worst = 0.0;
  for (vtkIdType i = 0; i < mine->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const double x = a->GetComponent(i, c), y = b->GetComponent(offset + i, c);
      worst = std::max(worst, std::abs(x - y) / std::max(1e-6, std::abs(y)));
    }
  }
  return worst;
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  bool ok = Check(rank, ranks >= 2, "runs on 2 or more ranks");

  const vtkSmartPointer<vtkPolyData> block = Block(), floor = Floor();
  vtkNew<vtkPolyData> empty;
  vtkPolyData* mine = rank == 0 ? block.Get() : rank == 1 ? floor.Get() : empty.Get();
  const vtkIdType offset = rank == 0 ? 0 : block->GetNumberOfPoints();

  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetConeAngle(90);
  light->SetPosition(0.3, 0.1, 2.0);
  light->SetFocalPoint(0, 0, 0);

  // The partitioned solve (collective on every rank).
  vtkNew<vtkGlobalIlluminationFilter> distributed;
  ok &= Check(rank, distributed->GetController() == controller.Get(), "the global controller by default");
  Configure(distributed, light);
  distributed->SetInputData(mine);
  distributed->Update();
  vtkPolyData* out = distributed->GetOutput();
  ok &= Check(rank, out->GetNumberOfPoints() == mine->GetNumberOfPoints(), "the output has this rank's points");
  ok &= Check(rank, Field(out, "LinkGI.Processes") == ranks, "LinkGI.Processes is the number of ranks");
  ok &= Check(rank, Field(out, "LinkGI.PartitionBytesReceived") > 0, "the partitions were exchanged");
  // Each rank links only its own points' rows; the bounces exchange 12 B per element, once
  // for the sky and once per bounce.
  const double elements = double(block->GetNumberOfPoints() + floor->GetNumberOfPoints());
  ok &= Check(rank, Field(out, "LinkGI.RadianceBytesExchanged") == 12.0 * elements * 3,
    "the radiance exchanges moved 12 B per element, 3 times (" +
      std::to_string(Field(out, "LinkGI.RadianceBytesExchanged")) + " B)");

  // One process lighting the appended surface, in rank order: the same scene.
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(block);
  append->AddInputData(floor);
  append->Update();
  vtkNew<vtkGlobalIlluminationFilter> whole;
  whole->SetController(nullptr);
  Configure(whole, light);
  whole->SetInputData(append->GetOutput());
  whole->Update();
  const double linksHere = Field(out, "LinkGI.LinksCompressed"), linksAll = Field(whole->GetOutput(), "LinkGI.LinksCompressed");
  ok &= Check(rank, rank > 1 ? linksHere == 0.0 : linksHere > 0.0 && linksHere < linksAll,
    "this rank links its own rows only (" + std::to_string(linksHere) + " of " + std::to_string(linksAll) + ")");
  if (mine->GetNumberOfPoints() > 0)
  {
    for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
    {
      const double d = Difference(out, whole->GetOutput(), offset, name);
      ok &= Check(rank, d <= 1e-4, std::string(name) + " equals one process's within 1e-4 (" + std::to_string(d) + ")");
    }
  }

  // The floor's shadow comes from rank 0's block: alone, rank 1 would light it.
  if (rank == 1)
  {
    vtkNew<vtkGlobalIlluminationFilter> alone;
    alone->SetController(nullptr);
    Configure(alone, light);
    alone->SetInputData(floor);
    alone->Update();
    vtkDataArray* shared = out->GetPointData()->GetArray("DirectIrradiance");
    vtkDataArray* own = alone->GetOutput()->GetPointData()->GetArray("DirectIrradiance");
    vtkIdType shadowed = 0;
    for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
    {
      shadowed += shared->GetComponent(i, 0) == 0.0 && own->GetComponent(i, 0) > 0.0;
    }
    ok &= Check(rank, shadowed >= 4, "rank 0's block shadows " + std::to_string(shadowed) + " floor points");
  }

  // A light move: no exchange, no new links, new light links.
  const double links = Field(out, "LinkGI.LinkBuilds"), lightLinks = Field(out, "LinkGI.LightLinkBuilds");
  light->SetPosition(-0.3, 0.2, 2.0);
  distributed->Modified();
  distributed->Update();
  out = distributed->GetOutput();
  ok &= Check(rank, Field(out, "LinkGI.PartitionBytesReceived") == 0, "a light move exchanges no surface");
  ok &= Check(rank, Field(out, "LinkGI.LinkBuilds") == links, "a light move builds no links");
  ok &= Check(rank, Field(out, "LinkGI.LightLinkBuilds") == lightLinks + 1, "a light move re-runs the light links");

  // Rank 1 aborts the next light move in its bounces, after the sky's exchange: every rank
  // leaves the update together (rank 1 with its warning, the others with an error that says
  // so) and keeps its previous output, instead of waiting for rank 1 in the next exchange;
  // the update after that completes everywhere, with one process's values.
  {
    vtkNew<vtkDoubleArray> before;
    before->DeepCopy(out->GetPointData()->GetArray("DirectIrradiance"));
    std::string messages;
    vtkNew<vtkCallbackCommand> onMessage;
    onMessage->SetClientData(&messages);
    onMessage->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData) {
      *static_cast<std::string*>(clientData) += static_cast<const char*>(callData);
    });
    vtkNew<vtkCallbackCommand> abortInBounces; // what a GUI's cancel button does, on rank 1 only
    abortInBounces->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
      auto* filter = static_cast<vtkAlgorithm*>(caller);
      if (filter->GetProgressText() && std::strstr(filter->GetProgressText(), "ounces"))
      {
        filter->SetAbortExecute(1);
      }
    });
    const unsigned long onError = distributed->AddObserver(vtkCommand::ErrorEvent, onMessage);
    const unsigned long onWarning = distributed->AddObserver(vtkCommand::WarningEvent, onMessage);
    const unsigned long onProgress = rank == 1 ? distributed->AddObserver(vtkCommand::ProgressEvent, abortInBounces) : 0;
    light->SetPosition(0.1, -0.3, 2.0);
    distributed->Modified();
    distributed->Update();
    out = distributed->GetOutput();
    ok &= Check(rank, rank == 1 ? messages.find("aborted") != std::string::npos :
                                  messages.find("failed on 1 of the other processes") != std::string::npos,
      "every rank leaves the update that rank 1 aborted (" + messages + ")");
    vtkDataArray* after = out->GetPointData()->GetArray("DirectIrradiance");
    bool kept = after && after->GetNumberOfTuples() == before->GetNumberOfTuples();
    for (vtkIdType i = 0; kept && i < before->GetNumberOfTuples(); ++i)
    {
      kept = after->GetComponent(i, 0) == before->GetComponent(i, 0);
    }
    ok &= Check(rank, kept, "and keeps its previous output");
    if (rank == 1)
    {
      distributed->RemoveObserver(onProgress);
      distributed->SetAbortExecute(0);
    }
    messages.clear();
    distributed->Modified();
    distributed->Update();
    out = distributed->GetOutput();
    whole->Modified();
    whole->Update();
    ok &= Check(rank, messages.empty(), "the next update completes everywhere (" + messages + ")");
    if (mine->GetNumberOfPoints() > 0)
    {
      const double d = Difference(out, whole->GetOutput(), offset, "IndirectIrradiance");
      ok &= Check(rank, d <= 1e-4, "with one process's values (" + std::to_string(d) + ")");
    }
    distributed->RemoveObserver(onError);
    distributed->RemoveObserver(onWarning);
  }

  // Asynchronous: every process solves the global surface in the background (no MPI from
  // that thread) and outputs its own points of the newest result, one process's values; a
  // light move re-runs only the light links and the bounces.
  {
    vtkNew<vtkGlobalIlluminationFilter> async;
    Configure(async, light);
    async->SetAsynchronous(true);
    async->SetInputData(mine);
    async->Update();
    for (int move = 0; move < 2; ++move)
    {
      // Collective, as a render would be: all re-execute when any has a newer result.
      async->WaitForAsynchronousResult(600.0);
      async->Update();
      vtkPolyData* shown = async->GetOutput();
      const std::string when = move == 0 ? "the first asynchronous result" : "after a light move";
      const double newest = static_cast<double>(async->GetAsynchronousRequest());
      ok &= Check(rank, Field(shown, "LinkGI.ShownRequest") == newest && Field(shown, "LinkGI.Pending") == 0.0,
        when + " is shown (request " + std::to_string(Field(shown, "LinkGI.ShownRequest")) + " of " +
          std::to_string(newest) + ")");
      ok &= Check(rank, shown->GetNumberOfPoints() == mine->GetNumberOfPoints(), when + ": this rank's points");
      if (mine->GetNumberOfPoints() > 0)
      {
        for (const char* name : { "DirectIrradiance", "IndirectIrradiance" })
        {
          const double d = Difference(shown, whole->GetOutput(), offset, name);
          ok &= Check(rank, d <= 1e-4, when + ": " + name + " equals one process's (" + std::to_string(d) + ")");
        }
      }
      if (move == 1)
      {
        ok &= Check(rank, Field(shown, "LinkGI.LinkBuilds") == 1.0 && Field(shown, "LinkGI.LightLinkBuilds") == 2.0,
          "a light move re-ran the light links only (" + std::to_string(Field(shown, "LinkGI.LinkBuilds")) + " link builds, " +
            std::to_string(Field(shown, "LinkGI.LightLinkBuilds")) + " light link builds)");
        break;
      }
      light->SetPosition(0.3, 0.1, 2.0);
      whole->Modified();
      whole->Update();
      async->Modified();
      async->Update();
    }
  }

  // Rank 0's memory budget (64 KiB) is too small for its part of the update, the others'
  // (the machine's) is not: the ranks agree, so all refuse the update with an error, instead
  // of rank 0 refusing alone while the others wait for it in the first exchange.
  {
    vtkNew<vtkGlobalIlluminationFilter> budgeted;
    Configure(budgeted, light);
    budgeted->SetInputData(mine);
    budgeted->SetMemoryBudget(rank == 0 ? 1.0 / 16.0 : 0.0);
    std::string error;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetClientData(&error);
    onError->SetCallback([](vtkObject*, unsigned long, void* clientData, void* callData) {
      *static_cast<std::string*>(clientData) += static_cast<const char*>(callData);
    });
    budgeted->AddObserver(vtkCommand::ErrorEvent, onError);
    budgeted->Update();
    ok &= Check(rank, error.find("Not enough memory") != std::string::npos,
      "every rank refuses the update over rank 0's budget (" + error + ")");
    ok &= Check(rank, rank == 0 || error.find("Not enough memory on another process") != std::string::npos,
      "the other ranks say whose budget it was");
    ok &= Check(rank, budgeted->GetOutput()->GetNumberOfPoints() == 0, "a refused first update outputs nothing");
  }

  // Instant radiosity, photon mapping and implicit visibility split their gathers by rows as
  // well: instant radiosity exchanges E_ind once, photon mapping its clusters' irradiance and
  // distances, implicit visibility the sky's irradiance and each bounce's E_ind (2 bounces);
  // the arrays are those of one process.
  for (const int method : { vtkGlobalIlluminationFilter::INSTANT_RADIOSITY, vtkGlobalIlluminationFilter::PHOTON_MAPPING,
         vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY })
  {
    const std::string label = method == vtkGlobalIlluminationFilter::INSTANT_RADIOSITY ? "instant radiosity"
      : method == vtkGlobalIlluminationFilter::PHOTON_MAPPING                          ? "photon mapping"
                                                                                        : "implicit visibility";
    vtkNew<vtkGlobalIlluminationFilter> rows, one;
    for (vtkGlobalIlluminationFilter* f : { rows.Get(), one.Get() })
    {
      Configure(f, light);
      f->SetMethod(method);
      f->SetNumberOfPhotons(32768);
      f->SetNumberOfClusters(256);
      f->SetFinalGatherRays(64);
    }
    rows->SetInputData(mine);
    rows->Update();
    one->SetController(nullptr);
    one->SetInputData(append->GetOutput());
    one->Update();
    vtkPolyData* lit = rows->GetOutput();
    const double exchanges = method == vtkGlobalIlluminationFilter::INSTANT_RADIOSITY ? 1.0
      : method == vtkGlobalIlluminationFilter::PHOTON_MAPPING                          ? 2.0
                                                                                        : 3.0;
    ok &= Check(rank, Field(lit, "LinkGI.RadianceBytesExchanged") == 12.0 * elements * exchanges,
      label + " exchanged " + std::to_string(int(exchanges)) + " vectors of 12 B per element (" +
        std::to_string(Field(lit, "LinkGI.RadianceBytesExchanged")) + " B)");
    if (mine->GetNumberOfPoints() > 0)
    {
      for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
      {
        const double d = Difference(lit, one->GetOutput(), offset, name);
        ok &= Check(rank, d <= 1e-4, label + "'s " + name + " equals one process's (" + std::to_string(d) + ")");
      }
    }
  }

  // The floor split in two halves with a layer of ghost cells each (rank 2: nothing). The
  // ghost points take their owner's values: those of the owner's copy in one process's
  // lighting of the same global surface (each half without its ghost cells, in rank order).
  {
    const double layer = 2.0 / 24.0;
    const vtkSmartPointer<vtkPolyData> half = Half(floor, rank, layer);
    vtkNew<vtkGlobalIlluminationFilter> split;
    Configure(split, light);
    split->SetInputData(half);
    split->Update();
    vtkPolyData* lit = split->GetOutput();
    vtkNew<vtkAppendPolyData> parts;
    for (int r = 0; r < 2; ++r)
    {
      vtkNew<vtkPolyData> noGhostCells;
      noGhostCells->DeepCopy(Half(floor, r, layer));
      noGhostCells->BuildCells(); // without the ghost cells, every point kept (as the filter sends it)
      vtkUnsignedCharArray* cellGhosts = noGhostCells->GetCellGhostArray();
      for (vtkIdType c = 0; c < noGhostCells->GetNumberOfCells(); ++c)
      {
        if (cellGhosts->GetValue(c))
        {
          noGhostCells->DeleteCell(c);
        }
      }
      noGhostCells->RemoveDeletedCells();
      parts->AddInputData(noGhostCells);
    }
    parts->Update();
    vtkNew<vtkGlobalIlluminationFilter> reference;
    reference->SetController(nullptr);
    Configure(reference, light);
    reference->SetInputData(parts->GetOutput());
    reference->Update();
    if (rank <= 1)
    {
      // Each point against one process's value: its own place for its own points, the
      // owner's copy (the same place in the other half, not a ghost there) for ghost points.
      const vtkIdType firstHalf = Half(floor, 0, layer)->GetNumberOfPoints();
      const vtkIdType halfOffset = rank == 0 ? 0 : firstHalf, otherOffset = rank == 0 ? firstHalf : 0;
      const vtkSmartPointer<vtkPolyData> other = Half(floor, 1 - rank, layer);
      vtkUnsignedCharArray* ghosts = half->GetPointGhostArray();
      vtkUnsignedCharArray* otherGhosts = other->GetPointGhostArray();
      vtkPolyData* whole = reference->GetOutput();
      vtkIdType ghostPoints = 0, matched = 0;
      double worstOwn = 0.0, worstGhost = 0.0, largestGhost = 0.0;
      for (vtkIdType i = 0; i < half->GetNumberOfPoints(); ++i)
      {
        vtkIdType at = halfOffset + i;
        const bool ghost = (ghosts->GetValue(i) & vtkDataSetAttributes::DUPLICATEPOINT) != 0;
        if (ghost)
        {
          ++ghostPoints;
          at = -1;
          const double* p = half->GetPoint(i);
          for (vtkIdType j = 0; j < other->GetNumberOfPoints() && at < 0; ++j)
          {
            const double* q = other->GetPoint(j);
            if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2] &&
              !(otherGhosts->GetValue(j) & vtkDataSetAttributes::DUPLICATEPOINT))
            {
              at = otherOffset + j;
            }
          }
          if (at < 0)
          {
            continue;
          }
          ++matched;
        }
        for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
        {
          vtkDataArray* a = lit->GetPointData()->GetArray(name);
          vtkDataArray* b = whole->GetPointData()->GetArray(name);
          for (int c = 0; c < 3; ++c)
          {
            const double x = a->GetComponent(i, c), y = b->GetComponent(at, c);
            const double d = std::abs(x - y) / std::max(1e-6, std::abs(y));
            (ghost ? worstGhost : worstOwn) = std::max(ghost ? worstGhost : worstOwn, d);
            if (ghost)
            {
              largestGhost = std::max(largestGhost, std::abs(x));
            }
          }
        }
      }
      ok &= Check(rank, ghostPoints > 0 && matched == ghostPoints,
        std::to_string(ghostPoints) + " ghost points, each with an owner's copy (" + std::to_string(matched) + ")");
      ok &= Check(rank, largestGhost > 0.0, "the ghost points are lit");
      ok &= Check(rank, worstGhost <= 1e-4,
        "ghost points equal their owner's values within 1e-4 (" + std::to_string(worstGhost) + ")");
      ok &= Check(rank, worstOwn <= 1e-4,
        "the half's own points equal one process's within 1e-4 (" + std::to_string(worstOwn) + ")");
    }
  }

  int all = ok ? 1 : 0, every = 0;
  controller->AllReduce(&all, &every, 1, vtkCommunicator::MIN_OP);
  controller->Finalize();
  return every ? 0 : 1;
}
