// vtkGlobalIlluminationFilter's incremental updates: what a change of the light, the albedo
// or the options recomputes, and which changes of the input are a new surface.
#include "FilterTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkMath.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
const double Origin[3] = { 0, 0, 0 };
}

TEST(GlobalIlluminationFilter, LightOrAlbedoChangesReuseTheLinks)
{
  auto filter = MakeFilter(MakeSphereOnFloor());
  const double lamp[3] = { 0.5, 0.5, 4 };
  vtkSmartPointer<vtkLight> light = MakeLight(lamp, Origin, 16);
  filter->AddLight(light);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  const double direct0 = Value(out, "DirectIrradiance", 0);

  light->SetPosition(-1, 0.5, 3); // the filter's MTime includes the light's
  filter->Update();
  EXPECT_EQ(Stat(out, "LinkBuilds"), 1.0);
  EXPECT_EQ(Stat(out, "BvhBuilds"), 1.0);
  EXPECT_EQ(Stat(out, "LightLinkBuilds"), 2.0);
  EXPECT_EQ(Stat(out, "BounceRuns"), 2.0);
  EXPECT_EQ(Stat(out, "MsLinks"), 0.0);
  EXPECT_NE(Value(out, "DirectIrradiance", 0), direct0);

  filter->SetAlbedo(0.3, 0.5, 0.7);
  filter->Update();
  EXPECT_EQ(Stat(out, "LinkBuilds"), 1.0);
  EXPECT_EQ(Stat(out, "LightLinkBuilds"), 2.0);
  EXPECT_EQ(Stat(out, "BounceRuns"), 3.0);
  for (int c = 0; c < 3; ++c) // the new albedo is used (the colours are gathered again)
  {
    const double e = Value(out, "DirectIrradiance", 0, c) + Value(out, "IndirectIrradiance", 0, c);
    EXPECT_GT(e, 0.0);
    EXPECT_NEAR(Value(out, "Radiance", 0, c), (0.3 + 0.2 * c) / vtkMath::Pi() * e, 1e-5 * e);
  }

  filter->Update(); // nothing changed: no execution at all
  EXPECT_EQ(Stat(out, "BounceRuns"), 3.0);

  filter->SetNumberOfBounces(5);
  filter->Update();
  EXPECT_EQ(Stat(out, "LinkBuilds"), 1.0);
  EXPECT_EQ(Stat(out, "BounceRuns"), 4.0);

  filter->SetRaysPerVertex(16); // new directions: new links
  filter->Update();
  EXPECT_EQ(Stat(out, "LinkBuilds"), 2.0);
}

// A new data object of the same surface (a colour map's shallow copy with its new albedo
// array) keeps the triangulation and takes its own colours; the points or the cells changed
// in place (their storage only, as VTK 9.1's cell arrays do not see that) are a new surface.
// Each result equals a fresh filter's.
TEST(GlobalIlluminationFilter, TheSurfaceFollowsItsGeometryNotItsDataObject)
{
  vtkSmartPointer<vtkPolyData> scene = MakeSphereOnFloor();
  scene->GetPointData()->SetNormals(nullptr); // normals from the winding
  const vtkIdType points = scene->GetNumberOfPoints();
  const auto grey = [points](float value)
  {
    auto albedo = vtkSmartPointer<vtkFloatArray>::New();
    albedo->SetName("Albedo");
    albedo->SetNumberOfComponents(3);
    albedo->SetNumberOfTuples(points);
    albedo->Fill(value);
    return albedo;
  };
  scene->GetPointData()->AddArray(grey(0.3f));
  const auto configure = [](vtkGlobalIlluminationFilter* f)
  {
    f->SetAlbedoArrayName("Albedo");
    f->AddLight(Sun());
  };
  auto filter = MakeFilter(scene);
  configure(filter);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  const auto expectAsFresh = [&](vtkPolyData* input)
  {
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(input);
    auto fresh = MakeFilter(copy);
    configure(fresh);
    fresh->Update();
    for (const char* name : { "DirectIrradiance", "IndirectIrradiance" })
    {
      EXPECT_LT(RelativeDifference(out->GetPointData()->GetArray(name),
                  fresh->GetOutput()->GetPointData()->GetArray(name)), 1e-5)
        << name;
    }
  };

  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(scene);
  copy->GetPointData()->AddArray(grey(0.6f)); // replaces the copy's own "Albedo"
  filter->SetInputData(copy);
  filter->Update();
  EXPECT_EQ(Stat(out, "LinkBuilds"), 1.0);
  EXPECT_NEAR(Value(out, "Radiance", 0), 0.6 / vtkMath::Pi() *
      (Value(out, "DirectIrradiance", 0) + Value(out, "IndirectIrradiance", 0)), 1e-6);
  expectAsFresh(copy);

  // The floor (the first 20 x 20 quads) turned over through its connectivity array alone:
  // it faces away from the sun now.
  ASSERT_GT(Value(out, "DirectIrradiance", 0), 0.5);
  vtkCellArray* polys = copy->GetPolys();
  vtkDataArray* ids = polys->GetConnectivityArray();
  for (vtkIdType cell = 0; cell < 400; ++cell)
  {
    ASSERT_EQ(polys->GetCellSize(cell), 4);
    const vtkIdType first = polys->GetOffsetsArray()->GetComponent(cell, 0);
    const double second = ids->GetComponent(first + 1, 0);
    ids->SetComponent(first + 1, 0, ids->GetComponent(first + 3, 0));
    ids->SetComponent(first + 3, 0, second);
  }
  ids->Modified();
  copy->Modified(); // what makes the pipeline run again
  filter->Update();
  EXPECT_EQ(Value(out, "DirectIrradiance", 0), 0.0);
  expectAsFresh(copy);

  // The sphere raised through its points, in place.
  vtkPoints* xyz = copy->GetPoints();
  for (vtkIdType p = 21 * 21; p < points; ++p)
  {
    double x[3];
    xyz->GetPoint(p, x);
    xyz->SetPoint(p, x[0], x[1], x[2] + 0.2);
  }
  xyz->Modified();
  filter->Update();
  expectAsFresh(copy);
}
