/**
 * @class   vtkGlobalIlluminationGlobalCasters
 * @brief   the triangles of the other processes of a parallel run, for the shadow maps
 *
 * In a parallel run (pvbatch --mpi, a parallel pvserver, an MPI VTK program) every process
 * draws only its own partition, so a shadow that one process's geometry casts onto
 * another's would be missing at the partition boundary. Gather() collects the triangles of
 * every process through the global vtkMultiProcessController (an allgather of triangle
 * corner positions, 36 bytes per triangle) and keeps those of the other processes; a
 * mapper whose vtkGlobalIlluminationShading holds this object draws them into its shadow
 * maps besides its own triangles, so every process's maps hold the whole scene.
 *
 * Gather() is collective: every process of the global controller must call it, each with
 * its own partition (possibly empty or null), in the same order. It exchanges the
 * triangles only when some process's geometry changed (its points or cells are other
 * objects or were modified); otherwise it costs one reduction of a flag. Point data (a new
 * indirect irradiance, colours) does not count. With one process, or where VTK was built
 * without its parallel module, it gathers nothing and there is nothing to add.
 *
 * The gathered positions are in data coordinates (drawn with the actor's matrix, which is
 * the same on every process), stored as floats relative to the centre of the global
 * bounds. Past MaximumTriangles triangles of other processes (every process decides alike,
 * from the gathered counts and limits) each process sends a decimated proxy of its
 * triangles instead, at most its share of the limit (vertex clustering,
 * vtkQuadricClustering), with a warning: the shadows of the other partitions are then
 * approximate. With MaximumTriangles 0, or where even the proxies do not fit, nothing is
 * gathered and those shadows are missing.
 *
 * Cells marked as duplicates (ghost cells) are left out; polygons are fanned, strips split
 * into triangles; lines, vertices and non-polydata leaves cast nothing.
 *
 * @sa vtkGlobalIlluminationShading::SetGlobalCasters
 */
#ifndef vtkGlobalIlluminationGlobalCasters_h
#define vtkGlobalIlluminationGlobalCasters_h

#include "LinkGIRenderingGlobalIlluminationModule.h" // for export macro
#include "vtkObject.h"

#include <vector> // for std::vector

class vtkDataObject;

class LINKGIRENDERINGGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationGlobalCasters
  : public vtkObject
{
public:
  static vtkGlobalIlluminationGlobalCasters* New();
  vtkTypeMacro(vtkGlobalIlluminationGlobalCasters, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Collective over the global controller's processes: brings the other processes'
   * triangles up to date with `local`, this process's partition (a vtkPolyData, a
   * composite dataset of them, or null). Returns true if it exchanged triangles.
   */
  bool Gather(vtkDataObject* local);

  ///@{
  /**
   * The most triangles of other processes that are gathered. If any process would
   * receive more (under the least limit over the processes), every process sends a
   * decimated proxy instead (none at 0), with a warning. A change takes effect at the next Gather. The default value is
   * 20 000 000 (720 MB per process).
   */
  vtkSetClampMacro(MaximumTriangles, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumTriangles, vtkIdType);
  ///@}

  /// Whether a parallel module was built in (without it Gather never gathers).
  static bool IsParallel();

  /// The number of processes of the last Gather (1 before it).
  int GetNumberOfProcesses() const { return this->NumberOfProcesses; }

  /// The other processes' triangles: 9 floats (three corners) each, relative to Origin.
  const std::vector<float>& GetPositions() const { return this->Positions; }
  vtkIdType GetNumberOfTriangles() const
  {
    return static_cast<vtkIdType>(this->Positions.size() / 9);
  }

  /// The centre of the global bounds, to which the positions are relative.
  const double* GetOrigin() const VTK_SIZEHINT(3) { return this->Origin; }

  /// The bounds of the other processes' triangles (data coordinates); empty (min > max)
  /// when there are none.
  const double* GetBounds() const VTK_SIZEHINT(6) { return this->Bounds; }

  /// How many times Gather exchanged triangles; changes exactly when the positions do.
  int GetNumberOfGathers() const { return this->NumberOfGathers; }

  /// Bytes this process received in the last exchange (positions and counts).
  vtkIdType GetLastGatherBytes() const { return this->LastGatherBytes; }

  /// Whether the full triangles were over MaximumTriangles at the last exchange.
  bool GetOverLimit() const { return this->OverLimit; }

  /// Whether the last exchange sent decimated proxies (over the limit, with a limit above 0).
  bool GetProxies() const { return this->Proxies; }

protected:
  vtkGlobalIlluminationGlobalCasters();
  ~vtkGlobalIlluminationGlobalCasters() override;

  vtkIdType MaximumTriangles = 20000000;

private:
  vtkGlobalIlluminationGlobalCasters(const vtkGlobalIlluminationGlobalCasters&) = delete;
  void operator=(const vtkGlobalIlluminationGlobalCasters&) = delete;

  std::vector<float> Positions;
  std::vector<double> Signature; // of the local geometry at the last Gather
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Bounds[6] = { 1.0, -1.0, 1.0, -1.0, 1.0, -1.0 };
  int NumberOfProcesses = 1;
  int NumberOfGathers = 0;
  vtkIdType LastGatherBytes = 0;
  bool OverLimit = false;
  bool Proxies = false;
  bool WarnedProxies = false;
  bool Gathered = false;
  vtkIdType GatheredMaximum = 0; // MaximumTriangles at the last exchange
};

#endif
