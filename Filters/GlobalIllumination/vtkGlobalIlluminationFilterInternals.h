// The state and the steps of vtkGlobalIlluminationFilter behind its API: scene building,
// options, progress, results and the asynchronous worker. Private to the module; split from
// vtkGlobalIlluminationFilter.cxx so that the filter's file holds its API and RequestData.
#ifndef vtkGlobalIlluminationFilterInternals_h
#define vtkGlobalIlluminationFilterInternals_h

#include "vtkGlobalIlluminationFilter.h"

#include "vtkGlobalIlluminationBlockMerger.h"
#include "vtkGlobalIlluminationPartitions.h"
#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "linkgi/AsyncSolver.h"
#include "linkgi/Resolution.h"

#include <memory>
#include <string>
#include <vector>

/// The objects something was made from, each at its modification time: it matches while
/// each is the same live object, unmodified. Weak, so it keeps none of them alive.
class vtkGlobalIlluminationSourceKey
{
public:
  void Set(const std::vector<vtkObject*>& objects);
  bool Matches(const std::vector<vtkObject*>& objects) const;
  void Clear() { this->Objects.clear(); }

private:
  std::vector<vtkWeakPointer<vtkObject>> Objects;
  std::vector<vtkMTimeType> Times;
};

struct vtkGlobalIlluminationFilter::vtkInternals
{
  /// Synchronous updates, at the resolution the properties ask for (the engine decides the
  /// proxy the memory budget needs, and refuses what does not combine).
  linkgi::ResolvedSolver Solver;
  bool RefinedUsed = false; // the output shows the refined surface of the last synchronous update
  /// The refined surface's points are its elements: the identity mapping for AttachResults.
  vtkGlobalIlluminationSceneBuilder::Mesh RefinedMesh;
  /// ProxyVertices and the Refinement properties as the engine takes them.
  linkgi::ResolutionOptions Resolution(vtkGlobalIlluminationFilter* self) const;
  void Update(vtkGlobalIlluminationFilter* self, const linkgi::Scene& scene);
  const linkgi::Solution& Solution() const { return this->Solver.solution(); }
  const linkgi::SolverStats& Stats() const { return this->Solver.stats(); }
  /// The synchronous output's geometry: `input` itself, or after refinement the refined
  /// surface with the input's point arrays interpolated and its cell arrays inherited.
  void ShapeOutput(vtkPolyData* input, vtkPolyData* output);
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  vtkSmartPointer<vtkDataObject> LastOutput; // the last good output, handed out after errors
  std::vector<std::string> Warnings;         // the filter's own, for this update
  std::string RaysRounded; // why SetRaysPerVertex changed the value asked for, or empty

  // Input that is no vtkPolyData (composite, or another dataset) is merged into one
  // surface, lit as `Lit`, and delivered back onto its blocks.
  vtkGlobalIlluminationBlockMerger Merger;
  vtkNew<vtkPolyData> Lit;
  vtkPolyData* Surface(vtkGlobalIlluminationFilter* self, vtkDataObject* input);

  // Under MPI: the global surface of every process's partition is lit as
  // `GlobalLit`, and each process keeps the light of its own points.
  vtkGlobalIlluminationPartitions Partitions;
  vtkNew<vtkPolyData> GlobalLit;
  /// This process's rows of the global surface for the engine (Options), null alone.
  std::shared_ptr<const linkgi::Partition> ActivePartition;

  // The triangle mesh and what it was built from (vtkGlobalIlluminationGeometry::Sources, not the input
  // object: a shallow copy with a new colour array, as a new colour map makes, is the same
  // surface); rebuilt only when one of these changes, so a light-only or colour-only update
  // costs no triangulation.
  vtkGlobalIlluminationSceneBuilder::Mesh Mesh;
  std::uint64_t MeshVersion = 0; ///< counts rebuilds of Mesh
  vtkGlobalIlluminationSourceKey MeshSource;
  bool MeshComputeNormals = false;
  double MeshFeatureAngle = 0.0;
  // What Mesh.Scene's albedo and emission were gathered with: a render loop updates at every
  // light move, and gathering them again each time costs the render thread.
  std::string ColorsKey;
  vtkGlobalIlluminationSourceKey ColorsSource; ///< the albedo and emission arrays

  const linkgi::Scene& UpdateScene(vtkGlobalIlluminationFilter* self, vtkPolyData* input);
  linkgi::SolverOptions Options(vtkGlobalIlluminationFilter* self);
  linkgi::ProgressCallback Progress(vtkGlobalIlluminationFilter* self);
  /// The point arrays of `solution` (DirectIrradiance, ... and their Back twins).
  std::vector<vtkSmartPointer<vtkDataArray>> PointArrays(
    vtkGlobalIlluminationFilter* self, const linkgi::Solution& solution);
  /// The field value LinkGI.Lamps: 1 where a light is a lamp (falls off with distance).
  void AddLamps(vtkPolyData* output) const;
  void AttachResults(vtkGlobalIlluminationFilter* self, vtkPolyData* output, double msFilter,
    const linkgi::Solution& solution, const linkgi::SolverStats& stats);

  // Asynchronous mode: the worker, and the request whose result the output shows.
  std::unique_ptr<linkgi::AsyncSolver> Async;
  std::uint64_t ShownRequest = 0;
  std::uint32_t ShownStage = 0; // ... and which of its progressive stages
  /// The point arrays of the shown result, kept while it stays the newest: a render loop
  /// re-executes the filter at every light move, and arrays made anew each time would make
  /// the mapper rebuild all its buffers each frame. Kept for the result object, the mesh
  /// (MeshVersion) and TwoSided they were made for; a null result stands for the black
  /// arrays shown before the first result.
  struct ShownArrays
  {
    std::shared_ptr<const linkgi::AsyncResult> Result;
    std::uint64_t MeshVersion = 0;
    bool TwoSided = false;
    std::vector<vtkSmartPointer<vtkDataArray>> Arrays;
  } Shown;
  std::uint64_t LastRequest = 0; // the newest request's id
  std::vector<std::string> Announced; // the warnings of the last asynchronous update, logged once
  bool SolveAsynchronously(vtkGlobalIlluminationFilter* self, vtkPolyData* input, vtkPolyData* output);

  /// The filter's warnings of this update, then the engine's.
  std::vector<std::string> AllWarnings() const
  {
    std::vector<std::string> all = this->Warnings;
    const auto& engine = this->Stats().warnings;
    all.insert(all.end(), engine.begin(), engine.end());
    return all;
  }
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationFilterInternals.h
