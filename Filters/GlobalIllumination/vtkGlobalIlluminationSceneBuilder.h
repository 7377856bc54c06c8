/**
 * @class   vtkGlobalIlluminationSceneBuilder
 * @brief   converts VTK data into the LinkGI engine's scene and maps results back
 *
 * vtkGlobalIlluminationFilter keeps its RequestData to plumbing; the conversions live here
 * so that tests can call them without a pipeline. Not wrapped and not installed.
 *
 * Elements: the engine solves per vertex of a triangle mesh whose vertices are split at
 * sharp edges. BuildMesh triangulates the input's polygons and strips, computes normals
 * when asked (vtkPolyDataNormals with splitting, which appends the split copies after the
 * original points) and keeps only the points that triangles use. Every element remembers
 * its input point, every triangle its input cell, so that arrays can be read from the
 * input and results written back onto it. The cells are taken in a canonical order
 * (CanonicalCells), so the same surface makes the same scene whatever order its cells come
 * in, and the engine relinks nothing for a reordering alone.
 *
 * Every function throws linkgi::Error with a sentence naming the problem.
 */

#ifndef vtkGlobalIlluminationSceneBuilder_h
#define vtkGlobalIlluminationSceneBuilder_h

#include "LinkGIFiltersGlobalIlluminationModule.h" // for export macro
#include "vtkGlobalIlluminationLights.h"           // for vtkGlobalIlluminationLights::Status
#include "vtkSmartPointer.h"                       // for vtkSmartPointer
#include "vtkType.h"                               // for vtkIdType

#include "linkgi/Orientation.h" // for linkgi::SurfaceOrientation
#include "linkgi/Scene.h"  // for linkgi::Scene
#include "linkgi/Solver.h" // for linkgi::SolverStats

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

class vtkCellArray;
class vtkDataArray;
class vtkFieldData;
class vtkFloatArray;
class vtkImageData;
class vtkLight;
class vtkPolyData;

class LINKGIFILTERSGLOBALILLUMINATION_EXPORT vtkGlobalIlluminationSceneBuilder
{
public:
  /// The triangle mesh handed to the engine and the maps back to the input.
  struct Mesh
  {
    /// positions, normals and triangles; the shading fields are left empty.
    linkgi::Scene Scene;
    std::vector<vtkIdType> ElementPoint; ///< input point id of each element
    std::vector<vtkIdType> TriangleCell; ///< input cell id of each triangle
    vtkIdType InputPointCount = 0;
    bool NormalsComputed = false;
    /// The engine's positions are the input's minus Origin (the centre of the surface's
    /// bounds, in double precision): single precision then resolves a surface at UTM
    /// coordinates as finely as one at the origin, and a translation changes no result.
    std::array<double, 3> Origin{};
    /// What BuildMesh noticed about the geometry, for every update's LinkGI.Warnings.
    std::vector<std::string> Warnings;
    /// The closed surfaces whose normals point inward, and which of them OrientToLights
    /// turned outward (their normals in Scene are negated).
    linkgi::SurfaceOrientation Orientation;
    std::vector<unsigned char> Flipped;
  };

  /**
   * Triangulates the polygons and strips of `input` (vertices and lines are ignored), and
   * takes normals from the input's point normals, or computes them with vtkPolyDataNormals
   * (splitting at `featureAngle` degrees) when `computeNormals` is set or the input has
   * none, and finds the closed surfaces whose normals point inward
   * (linkgi::findInwardSurfaces). Throws for an input without polygons or strips and for
   * non-finite coordinates.
   */
  static Mesh BuildMesh(vtkPolyData* input, bool computeNormals, double featureAngle);

  /**
   * The cells of `cells` that have at least `minimumSize` points, in an order that depends
   * only on the cells, not on the order they come in: by their three lowest point ids
   * (whatever point a cell's list starts from and whichever way it winds), ties by all
   * their point ids, then as listed, then the same cell twice in its input order. `index`
   * gets the place in `cells` of each cell of the result. VTK 9.1's vtkGeometryFilter emits
   * an unstructured grid's faces in another order at every execution (its threads' pieces
   * are joined as they finish); without this, a static time series would relink at every
   * step. Returns `cells` itself where it is already in that order; O(n log n) otherwise.
   */
  static vtkSmartPointer<vtkCellArray> CanonicalCells(
    vtkCellArray* cells, vtkIdType minimumSize, std::vector<vtkIdType>& index);

  /**
   * Lights every inward closed surface of `mesh` from the side its lights are on, once the
   * scene has its lights and emission: a surface with a light inside (a room) keeps its
   * normals, one without (an object wound inside out, like the Stanford bunny's PLY file)
   * has them turned outward. With `turn` false (two-sided elements, lit on both sides
   * anyway, front arrays on the normals' side) every surface keeps the input's normals.
   * Returns the warning that says what was turned, if anything.
   */
  static std::vector<std::string> OrientToLights(Mesh& mesh, bool turn);

  /**
   * One linear RGB value per element, read from the array `arrayName` of the input's point
   * data (`association` = vtkDataObject::FIELD_ASSOCIATION_POINTS) or cell data
   * (FIELD_ASSOCIATION_CELLS; an element gets the mean of its triangles' cells). With no
   * name every element gets `fallback`. Tuples are read by vtkGlobalIlluminationColors::Read
   * (unclamped: the engine validates them). `role` names the array in error messages
   * ("albedo").
   */
  static std::vector<linkgi::Vec3f> GatherColors(vtkPolyData* input, const Mesh& mesh,
    const char* arrayName, int association, const linkgi::Vec3f& fallback, const char* role);

  /**
   * One value per triangle of `mesh` from the 1-component array `arrayName` of the input's
   * cell data (the triangle's cell), or else of its point data: the value most of the
   * triangle's three points have (the first point's when all differ) with `majority`, their
   * mean without. Throws, naming `role` ("material"), for a missing or non-numeric array, or
   * one of other than 1 component.
   */
  static std::vector<double> GatherTriangleValues(vtkPolyData* input, const Mesh& mesh,
    const char* arrayName, bool majority, const char* role);

  /**
   * Converts a vtkLight as vtkGlobalIlluminationLights::Convert does (the mapper uses the
   * same function) into the engine's light, positioned relative to `origin` (the mesh's
   * Origin); `out` is written only if that returns CONVERTED.
   */
  static vtkGlobalIlluminationLights::Status ConvertLight(
    vtkLight* light, double scale, const std::array<double, 3>& origin, linkgi::Light& out);

  /**
   * A constant sky `color`, multiplied by the lat-long `texture` when one is given (its
   * point scalars, read by vtkGlobalIlluminationColors::Read). The image's last row (largest j, the top
   * of a picture read by VTK's image readers) looks along +Y.
   */
  static linkgi::Environment ConvertEnvironment(const double color[3], vtkImageData* texture);

  /**
   * Per input point, the mean of `values[offset + e]` over the elements e that are copies
   * of it (one element, or several where normals were split). Points that no triangle uses
   * (only in vertices and lines) get 0. Returns a 3-component float array named `name`.
   */
  static vtkSmartPointer<vtkFloatArray> MapToPoints(const Mesh& mesh,
    const std::vector<linkgi::Vec3f>& values, std::size_t offset, const char* name);

  /**
   * The solver's counters and stage times, the backend that ran, `msFilter` (all of
   * RequestData) and the warnings (`filterWarnings`, then the engine's) as one-tuple field
   * arrays named "LinkGI.<name>".
   */
  static void AddStatistics(vtkFieldData* fieldData, const linkgi::SolverStats& stats,
    double msFilter, const std::vector<std::string>& filterWarnings);

  /// One-tuple field array "LinkGI.<name>": unsigned 64-bit, double or string.
  static void AddFieldValue(vtkFieldData* fieldData, const std::string& name, std::uint64_t value);
  static void AddFieldValue(vtkFieldData* fieldData, const std::string& name, double value);
  static void AddFieldValue(vtkFieldData* fieldData, const std::string& name, const std::string& value);
};

#endif
// VTK-HeaderTest-Exclude: vtkGlobalIlluminationSceneBuilder.h
