#include "vtkGlobalIlluminationSceneBuilder.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkGlobalIlluminationColors.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkTriangleFilter.h"

#include "linkgi/Error.h"
#include "linkgi/Orientation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace
{
// Names of the id arrays carried through triangulation and normal splitting.
const char* const PointIdsName = "vtkGlobalIlluminationPointIds";
const char* const CellIdsName = "vtkGlobalIlluminationCellIds";

[[noreturn]] void Fail(const std::string& message)
{
  throw linkgi::Error(message);
}

vtkSmartPointer<vtkIdTypeArray> IdRange(const char* name, vtkIdType first, vtkIdType count)
{
  auto ids = vtkSmartPointer<vtkIdTypeArray>::New();
  ids->SetName(name);
  ids->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    ids->SetValue(i, first + i);
  }
  return ids;
}

// Marks the points used by the cells of `cells`.
void MarkUsed(vtkCellArray* cells, std::vector<unsigned char>& used)
{
  if (!cells)
  {
    return;
  }
  auto it = vtk::TakeSmartPointer(cells->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* pts;
    it->GetCurrentCell(n, pts);
    for (vtkIdType k = 0; k < n; ++k)
    {
      used[pts[k]] = 1;
    }
  }
}

// NaN or infinite coordinates would poison the ray tracer and vtkPolyDataNormals alike.
void CheckFinite(vtkPolyData* input)
{
  const vtkIdType n = input->GetNumberOfPoints();
  std::vector<unsigned char> used(static_cast<std::size_t>(n), 0);
  MarkUsed(input->GetPolys(), used);
  MarkUsed(input->GetStrips(), used);
  vtkIdType bad = 0, first = -1;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (used[i] && !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      first = bad++ == 0 ? i : first;
    }
  }
  if (bad > 0)
  {
    std::ostringstream msg;
    msg << "The input has " << bad << " surface point(s) with NaN or infinite coordinates"
        << " (the first is point " << first << "); remove or repair them before lighting.";
    Fail(msg.str());
  }
}

// The cells of `cells` in canonical order (CanonicalCells), their ids (`firstId` + their
// index) appended to `ids`.
vtkSmartPointer<vtkCellArray> InCanonicalOrder(
  vtkCellArray* cells, vtkIdType firstId, vtkIdType minimumSize, vtkIdTypeArray* ids)
{
  std::vector<vtkIdType> index;
  vtkSmartPointer<vtkCellArray> sorted =
    vtkGlobalIlluminationSceneBuilder::CanonicalCells(cells, minimumSize, index);
  for (vtkIdType c : index)
  {
    ids->InsertNextValue(firstId + c);
  }
  return sorted;
}

// Only points, surface cells (in canonical order: any order of the same cells makes the
// same scene) and the two id arrays go through the VTK filters.
vtkSmartPointer<vtkPolyData> SurfaceWithIds(vtkPolyData* input)
{
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(input->GetPoints());
  surface->GetPointData()->AddArray(IdRange(PointIdsName, 0, input->GetNumberOfPoints()));
  auto cellIds = vtkSmartPointer<vtkIdTypeArray>::New();
  cellIds->SetName(CellIdsName);
  cellIds->Allocate(input->GetNumberOfPolys() + input->GetNumberOfStrips());
  // Cell ids of vtkPolyData run over verts, then lines, then polys, then strips.
  const vtkIdType firstPoly = input->GetNumberOfVerts() + input->GetNumberOfLines();
  surface->SetPolys(InCanonicalOrder(input->GetPolys(), firstPoly, 0, cellIds));
  // Strips of fewer than 3 points hold no triangle, and crash vtkTriangleFilter (VTK 9.1
  // reads the first points of every strip): left out, the others keep their cell ids.
  surface->SetStrips(
    InCanonicalOrder(input->GetStrips(), firstPoly + input->GetNumberOfPolys(), 3, cellIds));
  surface->GetCellData()->AddArray(cellIds);
  return surface;
}

vtkSmartPointer<vtkPolyData> Triangulate(vtkPolyData* surface)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(surface);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  return triangles->GetOutput();
}

vtkSmartPointer<vtkPolyData> SplitNormals(vtkPolyData* triangles, double featureAngle)
{
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(triangles);
  normals->SetFeatureAngle(featureAngle);
  normals->SplittingOn();
  normals->ConsistencyOn();
  normals->NonManifoldTraversalOn();
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOff();
  normals->Update();
  return normals->GetOutput();
}

linkgi::Vec3f ToVec3f(const double v[3])
{
  return { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
}

// The centre of the bounds of the points that triangles use.
std::array<double, 3> BoundsCentre(vtkPolyData* mesh, const std::vector<unsigned char>& used)
{
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[3] = { VTK_DOUBLE_MIN, VTK_DOUBLE_MIN, VTK_DOUBLE_MIN };
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    if (used[p])
    {
      double x[3];
      mesh->GetPoint(p, x);
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], x[k]);
        hi[k] = std::max(hi[k], x[k]);
      }
    }
  }
  std::array<double, 3> centre{};
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = lo[k] <= hi[k] ? 0.5 * (lo[k] + hi[k]) : 0.0;
  }
  return centre;
}

/// The share of a surface's area at bent normals (SurfaceOrientation::bentNormalArea)
/// from which given normals are replaced by computed ones: a CAD part exported with normals
/// averaged across its edges holds 40%, scanned models with their own normals and contours
/// with gradient normals 0-3%.
constexpr double kBentNormalShare = 0.1;

// Finds the inward closed surfaces (OrientToLights turns them), and warns where normals
// and winding disagree (LinkGI's filter and mappers follow the normals there, VTK's own
// two-sided lighting the winding).
void FindInwardSurfaces(vtkGlobalIlluminationSceneBuilder::Mesh& mesh)
{
  std::vector<std::uint64_t> points(mesh.ElementPoint.begin(), mesh.ElementPoint.end());
  mesh.Orientation = linkgi::findInwardSurfaces(mesh.Scene, points);
  mesh.Flipped.assign(mesh.Orientation.inward.size(), 0);
  const std::size_t against = mesh.Orientation.againstWinding;
  if (against > 0 && !mesh.NormalsComputed)
  {
    std::ostringstream msg;
    msg << against << " of " << mesh.Scene.triangleCount()
        << " triangles have point normals against their winding: LinkGI (this filter and"
        << " its mappers) lights the side the normals point to, while VTK's other mappers"
        << " draw that side dark. Turn ComputeNormals on, or fix the normals or the winding"
        << " of those cells.";
    mesh.Warnings.push_back(msg.str());
  }
}

/// What replacing the given normals of `given` (a mesh built with them) says.
std::string BentNormalsReplaced(const vtkGlobalIlluminationSceneBuilder::Mesh& given)
{
  std::ostringstream msg;
  msg << "The point normals of " << given.Orientation.bentNormals << " of " << given.Scene.vertexCount()
      << " points (" << std::lround(100.0 * given.Orientation.bentNormalArea)
      << "% of the surface's area) lie more than " << linkgi::kBentNormalDegrees
      << " degrees from every one of their triangles: normals averaged across sharp edges, which"
      << " would light those points as if their surface were tilted. The surface is lit with"
      << " normals computed from its triangles instead, split at sharp edges (FeatureAngle), as"
      << " with ComputeNormals on. To shade with the same normals, split the input's"
      << " (vtkPolyDataNormals; in ParaView, Generate Surface Normals).";
  return msg.str();
}
}

//------------------------------------------------------------------------------
std::vector<std::string> vtkGlobalIlluminationSceneBuilder::OrientToLights(Mesh& mesh, bool turn)
{
  std::size_t flipped = 0, triangles = 0;
  for (std::size_t i = 0; i < mesh.Orientation.inward.size(); ++i)
  {
    const linkgi::InwardSurface& surface = mesh.Orientation.inward[i];
    const unsigned char outward = turn && !linkgi::hasLightInside(mesh.Scene, surface) ? 1 : 0;
    if (outward != mesh.Flipped[i])
    {
      linkgi::flipNormals(mesh.Scene, surface);
      mesh.Flipped[i] = outward;
    }
    flipped += outward;
    triangles += outward ? surface.triangles.size() : 0;
  }
  if (flipped == 0)
  {
    return {};
  }
  std::ostringstream msg;
  msg << flipped << " closed surface(s) (" << triangles << " triangles) have normals pointing"
      << " inward and no light inside; they are lit from outside. To fix the data itself:"
      << " vtkPolyDataNormals with AutoOrientNormalsOn (ParaView: Generate Surface Normals).";
  return { msg.str() };
}

namespace
{
linkgi::Vec3f ColorOf(vtkDataArray* array, vtkIdType tuple)
{
  return ToVec3f(vtkGlobalIlluminationColors::Read(array, tuple).data());
}
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationSceneBuilder::Mesh vtkGlobalIlluminationSceneBuilder::BuildMesh(
  vtkPolyData* input, bool computeNormals, double featureAngle)
{
  if (!input || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    std::ostringstream msg;
    msg << "The input has no polygons or triangle strips to illuminate";
    if (input)
    {
      msg << " (it has " << input->GetNumberOfVerts() << " vertex and "
          << input->GetNumberOfLines() << " line cells, which receive no light)";
    }
    const bool pointCloud = input && input->GetNumberOfLines() == 0 &&
      (input->GetNumberOfVerts() > 0 || input->GetNumberOfPoints() > 0);
    msg << (pointCloud
        ? "; a point cloud has no surface to light: reconstruct one first (e.g. "
          "vtkSurfaceReconstructionFilter and vtkContourFilter, or vtkDelaunay2D for a height "
          "field), or draw the points without global illumination."
        : "; extract a surface first, e.g. with vtkDataSetSurfaceFilter.");
    Fail(msg.str());
  }
  CheckFinite(input);

  vtkDataArray* inputNormals = input->GetPointData()->GetNormals();
  if (inputNormals && !computeNormals &&
    inputNormals->GetNumberOfTuples() < input->GetNumberOfPoints())
  {
    std::ostringstream msg;
    msg << "The input's point normals have " << inputNormals->GetNumberOfTuples()
        << " tuples for " << input->GetNumberOfPoints()
        << " points; fix them or turn ComputeNormals on.";
    Fail(msg.str());
  }
  Mesh mesh;
  mesh.InputPointCount = input->GetNumberOfPoints();
  mesh.NormalsComputed = computeNormals || !inputNormals;
  vtkSmartPointer<vtkPolyData> tri = Triangulate(SurfaceWithIds(input));
  if (mesh.NormalsComputed)
  {
    tri = SplitNormals(tri, featureAngle);
  }
  auto* pointIds = vtkIdTypeArray::SafeDownCast(tri->GetPointData()->GetArray(PointIdsName));
  auto* cellIds = vtkIdTypeArray::SafeDownCast(tri->GetCellData()->GetArray(CellIdsName));
  vtkDataArray* normals = mesh.NormalsComputed ? tri->GetPointData()->GetNormals() : inputNormals;
  if (!pointIds || !cellIds || !normals)
  {
    Fail("Triangulating the input lost its point or cell ids; this is a bug in LinkGI.");
  }

  // Elements: the points that triangles use, in point order.
  const vtkIdType meshPoints = tri->GetNumberOfPoints();
  std::vector<unsigned char> used(static_cast<std::size_t>(meshPoints), 0);
  MarkUsed(tri->GetPolys(), used);
  std::vector<linkgi::Index> element(static_cast<std::size_t>(meshPoints), linkgi::kInvalidIndex);
  mesh.Origin = BoundsCentre(tri, used);
  linkgi::Scene& scene = mesh.Scene;
  for (vtkIdType p = 0; p < meshPoints; ++p)
  {
    if (!used[p])
    {
      continue;
    }
    element[p] = static_cast<linkgi::Index>(scene.positions.size());
    const vtkIdType original = pointIds->GetValue(p);
    double x[3], n[3];
    tri->GetPoint(p, x);
    for (int k = 0; k < 3; ++k)
    {
      x[k] -= mesh.Origin[k]; // in double, before the rounding to float
    }
    normals->GetTuple(mesh.NormalsComputed ? p : original, n);
    scene.positions.push_back(ToVec3f(x));
    scene.normals.push_back(ToVec3f(n)); // the engine normalizes and repairs zero normals
    mesh.ElementPoint.push_back(original);
  }

  auto it = vtk::TakeSmartPointer(tri->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* pts;
    it->GetCurrentCell(n, pts);
    if (n != 3)
    {
      continue; // vtkTriangleFilter emits only triangles; be safe anyway
    }
    scene.triangles.push_back({ { element[pts[0]], element[pts[1]], element[pts[2]] } });
    mesh.TriangleCell.push_back(cellIds->GetValue(it->GetCurrentCellId()));
  }
  if (scene.triangles.empty())
  {
    Fail("The input's polygons and strips make no triangles (they have fewer than 3 points).");
  }
  FindInwardSurfaces(mesh);
  if (!mesh.NormalsComputed && mesh.Orientation.bentNormalArea >= kBentNormalShare)
  {
    Mesh split = BuildMesh(input, true, featureAngle);
    split.Warnings.insert(split.Warnings.begin(), BentNormalsReplaced(mesh));
    return split;
  }
  return mesh;
}

//------------------------------------------------------------------------------
std::vector<double> vtkGlobalIlluminationSceneBuilder::GatherTriangleValues(vtkPolyData* input,
  const Mesh& mesh, const char* arrayName, bool majority, const char* role)
{
  vtkDataArray* cells = input->GetCellData()->GetArray(arrayName);
  vtkDataArray* points = cells ? nullptr : input->GetPointData()->GetArray(arrayName);
  vtkDataArray* array = cells ? cells : points;
  if (!array)
  {
    Fail(std::string("The ") + role + " array '" + arrayName +
      "' is not a numeric array of the input's cell or point data; check the array name.");
  }
  if (array->GetNumberOfComponents() != 1)
  {
    Fail(std::string("The ") + role + " array '" + arrayName + "' has " +
      std::to_string(array->GetNumberOfComponents()) + " components; it needs 1.");
  }
  const vtkIdType needed = cells ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  if (array->GetNumberOfTuples() < needed)
  {
    Fail(std::string("The ") + role + " array '" + arrayName + "' has " +
      std::to_string(array->GetNumberOfTuples()) + " tuples, but the input has " + std::to_string(needed) +
      (cells ? " cells." : " points."));
  }
  const linkgi::Scene& scene = mesh.Scene;
  std::vector<double> values(scene.triangleCount());
  for (std::size_t t = 0; t < values.size(); ++t)
  {
    if (cells)
    {
      values[t] = cells->GetComponent(mesh.TriangleCell[t], 0);
      continue;
    }
    double v[3];
    for (int k = 0; k < 3; ++k)
    {
      v[k] = points->GetComponent(mesh.ElementPoint[scene.triangles[t].v[k]], 0);
    }
    values[t] = majority ? (v[1] == v[2] ? v[1] : v[0]) : (v[0] + v[1] + v[2]) / 3.0;
  }
  return values;
}

//------------------------------------------------------------------------------
std::vector<linkgi::Vec3f> vtkGlobalIlluminationSceneBuilder::GatherColors(vtkPolyData* input,
  const Mesh& mesh, const char* arrayName, int association, const linkgi::Vec3f& fallback,
  const char* role)
{
  const std::size_t elements = mesh.ElementPoint.size();
  if (!arrayName || !*arrayName)
  {
    return std::vector<linkgi::Vec3f>(elements, fallback);
  }
  const bool onPoints = association == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (!onPoints && association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    Fail(std::string("The ") + role + " array association must be points or cells.");
  }
  vtkDataArray* array = onPoints ? input->GetPointData()->GetArray(arrayName)
                                 : input->GetCellData()->GetArray(arrayName);
  if (!array)
  {
    Fail(std::string("The ") + role + " array '" + arrayName + "' is not a numeric array of the input's " +
      (onPoints ? "point" : "cell") + " data; check the array name and association.");
  }
  const int components = array->GetNumberOfComponents();
  if (components != 1 && components != 3 && components != 4)
  {
    std::ostringstream msg;
    msg << "The " << role << " array '" << arrayName << "' has " << components
        << " components; a colour has 1 (grey), 3 (RGB) or 4 (RGBA, alpha unused).";
    Fail(msg.str());
  }
  const vtkIdType needed = onPoints ? input->GetNumberOfPoints() : input->GetNumberOfCells();
  if (array->GetNumberOfTuples() < needed)
  {
    std::ostringstream msg;
    msg << "The " << role << " array '" << arrayName << "' has " << array->GetNumberOfTuples()
        << " tuples, but the input has " << needed << (onPoints ? " points." : " cells.");
    Fail(msg.str());
  }

  std::vector<linkgi::Vec3f> colors(elements);
  if (onPoints)
  {
    for (std::size_t e = 0; e < elements; ++e)
    {
      colors[e] = ColorOf(array, mesh.ElementPoint[e]);
    }
    return colors;
  }
  // Cell colours: the mean over each element's triangles. Elements split at sharp edges
  // see only the cells on their side.
  std::vector<float> count(elements, 0.f);
  const auto& triangles = mesh.Scene.triangles;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    const linkgi::Vec3f c = ColorOf(array, mesh.TriangleCell[t]);
    for (linkgi::Index v : triangles[t].v)
    {
      colors[v] += c;
      count[v] += 1.f;
    }
  }
  for (std::size_t e = 0; e < elements; ++e)
  {
    colors[e] = count[e] > 0.f ? colors[e] / count[e] : fallback;
  }
  return colors;
}

//------------------------------------------------------------------------------
vtkGlobalIlluminationLights::Status vtkGlobalIlluminationSceneBuilder::ConvertLight(
  vtkLight* light, double scale, const std::array<double, 3>& origin, linkgi::Light& out)
{
  vtkGlobalIlluminationLights::Light l;
  const vtkGlobalIlluminationLights::Status status =
    vtkGlobalIlluminationLights::Convert(light, scale, l);
  if (status != vtkGlobalIlluminationLights::CONVERTED)
  {
    return status;
  }
  static_assert(int(linkgi::LightType::Point) == vtkGlobalIlluminationLights::Light::POINT &&
      int(linkgi::LightType::Spot) == vtkGlobalIlluminationLights::Light::SPOT &&
      int(linkgi::LightType::Directional) == vtkGlobalIlluminationLights::Light::DIRECTIONAL,
    "one numbering of the light types");
  out.type = static_cast<linkgi::LightType>(l.Type);
  const double local[3] = { l.Position[0] - origin[0], l.Position[1] - origin[1],
    l.Position[2] - origin[2] };
  out.position = ToVec3f(local);
  out.direction = ToVec3f(l.Direction.data());
  out.intensity = ToVec3f(l.Intensity.data());
  out.coneAngleDegrees = static_cast<float>(l.ConeAngle);
  out.spotExponent = static_cast<float>(l.Exponent);
  out.attenuation = ToVec3f(l.Attenuation.data());
  return status;
}

//------------------------------------------------------------------------------
linkgi::Environment vtkGlobalIlluminationSceneBuilder::ConvertEnvironment(
  const double color[3], vtkImageData* texture)
{
  linkgi::Environment environment;
  environment.color = ToVec3f(color);
  if (!texture)
  {
    return environment;
  }
  int dims[3];
  texture->GetDimensions(dims);
  vtkDataArray* scalars = texture->GetPointData()->GetScalars();
  if (!scalars || dims[0] < 1 || dims[1] < 1 || dims[2] != 1 ||
    scalars->GetNumberOfTuples() < static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    Fail("The environment texture must be a 2D image with point scalars (a lat-long map).");
  }
  environment.width = dims[0];
  environment.height = dims[1];
  environment.texels.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (int row = 0; row < dims[1]; ++row)
  {
    const vtkIdType j = dims[1] - 1 - row; // engine row 0 looks up (+Y): the image's top
    for (int col = 0; col < dims[0]; ++col)
    {
      const linkgi::Vec3f c = ColorOf(scalars, j * dims[0] + col);
      if (!linkgi::isFinite(c) || c.x < 0.f || c.y < 0.f || c.z < 0.f)
      {
        Fail("The environment texture has negative, NaN or infinite values; it must hold "
             "radiance (linear RGB >= 0).");
      }
      environment.texels[static_cast<std::size_t>(row) * dims[0] + col] = c;
    }
  }
  return environment;
}
