// vtkGlobalIlluminationFilter's Refinement: the output is the refined surface, the input's
// point arrays interpolated onto it and its cell arrays inherited, with the normals it was
// lit with; bad settings are named and keep the previous output.
#include "FilterTestUtilities.h"

#include "vtkCellData.h"
#include "vtkCellArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
/// A 4 x 4 floor of 2 x 2 cells under a point light near one corner: far too coarse for its
/// light, with a point array linear in x and y and a cell array of cell ids.
vtkSmartPointer<vtkGlobalIlluminationFilter> CoarseFloorFilter()
{
  vtkSmartPointer<vtkPolyData> floor = MakeFloor(2, 2);
  vtkNew<vtkFloatArray> linear;
  linear->SetName("Linear");
  vtkNew<vtkIntArray> ids;
  ids->SetName("CellId");
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    const double* p = floor->GetPoint(i);
    linear->InsertNextValue(static_cast<float>(3.0 * p[0] - 2.0 * p[1] + 1.0));
  }
  for (vtkIdType c = 0; c < floor->GetNumberOfCells(); ++c)
  {
    ids->InsertNextValue(static_cast<int>(c));
  }
  floor->GetPointData()->AddArray(linear);
  floor->GetCellData()->AddArray(ids);
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(floor);
  const double light[3] = { 1.2, 1.0, 0.8 }, origin[3] = { 0, 0, 0 };
  filter->AddLight(MakeLight(light, origin, 2.0));
  filter->SetBackendToCPU();
  filter->SetRaysPerVertex(16);
  return filter;
}
}

TEST(TestGlobalIlluminationRefinement, OutputIsTheRefinedSurfaceWithTheInputsArrays)
{
  auto filter = CoarseFloorFilter();
  EXPECT_FALSE(filter->GetRefinement()) << "off by default";
  filter->RefinementOn();
  filter->SetRefinementMaxVertices(400);
  filter->SetRefinementRounds(4);
  filter->Update();
  vtkPolyData* input = vtkPolyData::SafeDownCast(filter->GetInput());
  vtkPolyData* out = filter->GetOutput();
  ASSERT_GT(out->GetNumberOfPoints(), input->GetNumberOfPoints()) << "the light asks for points";
  EXPECT_LE(out->GetNumberOfPoints(), 400);
  for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance", "Linear" })
  {
    ASSERT_NE(PointArray(out, name), nullptr) << name;
    EXPECT_EQ(PointArray(out, name)->GetNumberOfTuples(), out->GetNumberOfPoints()) << name;
  }
  // A linear function is carried exactly by midpoint interpolation.
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double* p = out->GetPoint(i);
    ASSERT_NEAR(Value(out, "Linear", i), 3.0 * p[0] - 2.0 * p[1] + 1.0, 1e-5) << "point " << i;
    ASSERT_NEAR(p[2], 0.0, 1e-12) << "points stay on the surface";
  }
  // Each piece inherits the cell it lies in: its centroid is inside that cell's square.
  vtkDataArray* ids = out->GetCellData()->GetArray("CellId");
  ASSERT_NE(ids, nullptr);
  ASSERT_EQ(ids->GetNumberOfTuples(), out->GetNumberOfCells());
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    out->GetPolys()->GetCellAtId(c, npts, pts);
    ASSERT_EQ(npts, 3);
    double centroid[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int d = 0; d < 3; ++d)
      {
        centroid[d] += out->GetPoint(pts[k])[d] / 3.0;
      }
    }
    double bounds[6];
    input->GetCellBounds(static_cast<vtkIdType>(ids->GetTuple1(c)), bounds);
    EXPECT_TRUE(centroid[0] >= bounds[0] && centroid[0] <= bounds[1] && centroid[1] >= bounds[2] &&
      centroid[1] <= bounds[3])
      << "piece " << c << " is not inside cell " << ids->GetTuple1(c);
  }

  filter->RefinementOff();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), input->GetNumberOfPoints());
}

TEST(TestGlobalIlluminationRefinement, BadSettingsAreNamedAndKeepThePreviousOutput)
{
  auto filter = CoarseFloorFilter();
  filter->RefinementOn();
  filter->SetRefinementMaxVertices(200);
  filter->Update();
  vtkNew<vtkPolyData> good;
  good->DeepCopy(filter->GetOutput());

  const auto failsWith = [&](const char* words)
  {
    MessageCapture messages(filter);
    filter->Update();
    EXPECT_TRUE(messages.HasError(words)) << words;
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), good->GetNumberOfPoints());
    EXPECT_EQ(Value(filter->GetOutput(), "DirectIrradiance", 5), Value(good, "DirectIrradiance", 5));
  };
  filter->SetRefinementTolerance(-1.0);
  failsWith("tolerance");
  filter->SetRefinementTolerance(0.1);
  filter->SetRefinementRounds(0);
  failsWith("rounds");
  filter->SetRefinementRounds(3);
  filter->SetProxyVertices(4);
  failsWith("exclude each other");
  filter->SetProxyVertices(0);

  // A composite input cannot be replaced by one refined surface.
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetBlock(0, vtkPolyData::SafeDownCast(filter->GetInput()));
  vtkNew<vtkGlobalIlluminationFilter> composite;
  composite->SetInputData(blocks);
  composite->RefinementOn();
  MessageCapture messages(composite);
  composite->Update();
  EXPECT_TRUE(messages.HasError("vtkPolyData input"));
}

TEST(TestGlobalIlluminationRefinement, TheRefinedSurfaceCarriesTheNormalsItWasLitWith)
{
  // A coarse sphere without normals: the filter computes them, and a new point gets its edge
  // ends' normals averaged, not its flat faces'. The refined output, solved again as an
  // input, must give the same direct light; from its faces' normals it does not.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(8);
  sphere->SetPhiResolution(6);
  sphere->Update();
  vtkNew<vtkPolyData> input;
  input->DeepCopy(sphere->GetOutput());
  input->GetPointData()->Initialize(); // no normals
  const double position[3] = { 2.0, 1.5, 1.0 }, origin[3] = { 0, 0, 0 };
  vtkNew<vtkGlobalIlluminationFilter> refined;
  refined->SetInputData(input);
  refined->AddLight(MakeLight(position, origin, 4.0));
  refined->SetBackendToCPU();
  refined->SetLightOversampling(false);
  refined->SetRefinement(true);
  refined->Update();
  vtkPolyData* out = refined->GetOutput();
  ASSERT_GT(out->GetNumberOfPoints(), input->GetNumberOfPoints());
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr) << "the refined surface carries its normals";
  ASSERT_EQ(normals->GetNumberOfTuples(), out->GetNumberOfPoints());
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double* n = normals->GetTuple3(i);
    ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-5) << "point " << i;
  }

  const auto directOf = [&](vtkPolyData* surface) {
    vtkNew<vtkGlobalIlluminationFilter> again;
    again->SetInputData(surface);
    again->AddLight(MakeLight(position, origin, 4.0));
    again->SetBackendToCPU();
    again->SetLightOversampling(false);
    again->Update();
    std::vector<double> e;
    for (vtkIdType i = 0; i < again->GetOutput()->GetNumberOfPoints(); ++i)
    {
      e.push_back(Value(again->GetOutput(), "DirectIrradiance", i));
    }
    return e;
  };
  vtkNew<vtkPolyData> withNormals, facesOnly;
  withNormals->CopyStructure(out);
  withNormals->GetPointData()->SetNormals(normals);
  facesOnly->CopyStructure(out);
  const std::vector<double> relit = directOf(withNormals), fromFaces = directOf(facesOnly);
  double differs = 0.0, differsFromFaces = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double e = Value(out, "DirectIrradiance", i);
    differs = std::max(differs, std::abs(relit[static_cast<std::size_t>(i)] - e));
    differsFromFaces = std::max(differsFromFaces, std::abs(fromFaces[static_cast<std::size_t>(i)] - e));
  }
  EXPECT_LT(differs, 1e-4) << "the same normals, the same direct light";
  EXPECT_GT(differsFromFaces, 0.01) << "the faces' normals light it otherwise (else this test shows nothing)";
}
