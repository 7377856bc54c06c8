// vtkGlobalIlluminationFilter on bad input: a clear message naming the problem, no crash,
// and the previous output kept after an error or an abort.
#include "FilterTestUtilities.h"

#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkImageData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <gtest/gtest.h>

#include <limits>

using namespace linkgi_test;

namespace
{
const double Origin[3] = { 0, 0, 0 };

// A lit 4 x 4 floor filter, ready to update.
vtkSmartPointer<vtkGlobalIlluminationFilter> FloorFilter(vtkPolyData* input = nullptr)
{
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(input ? input : MakeFloor(1, 4).GetPointer());
  filter->SetRaysPerVertex(16);
  filter->AddLight(Sun());
  return filter;
}

// A copy of the points of `pd` (so that a test can break them without touching others).
vtkSmartPointer<vtkPolyData> WithOwnPoints(vtkPolyData* pd)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(pd);
  return copy;
}

bool AllZero(vtkPolyData* out, const char* name)
{
  vtkDataArray* array = PointArray(out, name);
  for (int c = 0; c < 3; ++c)
  {
    if (array->GetRange(c)[0] != 0.0 || array->GetRange(c)[1] != 0.0)
    {
      return false;
    }
  }
  return true;
}
}

TEST(GlobalIlluminationFilterBadInput, NoInputIsAnErrorNotACrash)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  MessageCapture executive(filter->GetExecutive());
  filter->Update(); // the pipeline reports the missing connection
  EXPECT_TRUE(executive.HasError("has 0 connections")) << "no input connection";
  filter->SetInputData(nullptr);
  filter->Update();
  EXPECT_FALSE(executive.Errors.empty());
}

TEST(GlobalIlluminationFilterBadInput, EmptyInputGivesAnEmptyOutputAndAWarning)
{
  vtkNew<vtkPolyData> empty;
  auto filter = FloorFilter(empty);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("The input is empty"));
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(GlobalIlluminationFilterBadInput, LinesAndVerticesOnlyIsAnError)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  vtkNew<vtkCellArray> lines, verts;
  const vtkIdType line[] = { 0, 1 }, vert[] = { 0 };
  lines->InsertNextCell(2, line);
  verts->InsertNextCell(1, vert);
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  input->SetLines(lines);
  input->SetVerts(verts);
  auto filter = FloorFilter(input);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasError("no polygons or triangle strips"));
  EXPECT_TRUE(messages.HasError("1 vertex and 1 line cells"));
}

TEST(GlobalIlluminationFilterBadInput, NonFiniteCoordinatesAreAnErrorAndKeepThePreviousOutput)
{
  vtkSmartPointer<vtkPolyData> input = WithOwnPoints(MakeFloor(1, 4));
  auto filter = FloorFilter(input);
  filter->Update();
  const double before = Value(filter->GetOutput(), "DirectIrradiance", 3);
  ASSERT_NEAR(before, 1.0, 1e-4);

  // New points (the previous output shares the old ones, as any shallow copy does).
  vtkNew<vtkPoints> broken;
  broken->DeepCopy(input->GetPoints());
  broken->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  broken->SetPoint(7, 0, std::numeric_limits<double>::infinity(), 0);
  input->SetPoints(broken);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasError("2 surface point(s) with NaN or infinite coordinates"));
  EXPECT_TRUE(messages.HasError("the first is point 3"));
  vtkPolyData* out = filter->GetOutput();
  ASSERT_NE(PointArray(out, "DirectIrradiance"), nullptr) << "the previous output is kept";
  EXPECT_EQ(Value(out, "DirectIrradiance", 3), before);
  EXPECT_TRUE(std::isfinite(out->GetPoint(3)[0]));
}

TEST(GlobalIlluminationFilterBadInput, DegenerateTrianglesAreDroppedWithAWarning)
{
  vtkSmartPointer<vtkPolyData> input = WithOwnPoints(MakeFloor(1, 4));
  const vtkIdType repeated[] = { 0, 0, 1 }, collinear[] = { 0, 1, 2 };
  input->GetPolys()->InsertNextCell(3, repeated);
  input->GetPolys()->InsertNextCell(3, collinear); // points 0, 1, 2 lie on one grid line
  auto filter = FloorFilter(input);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.HasWarning("degenerate"));
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(out->GetNumberOfPolys(), input->GetNumberOfPolys()) << "the output keeps them";
  EXPECT_NEAR(Value(out, "DirectIrradiance", 1), 1.0, 1e-4);
}

TEST(GlobalIlluminationFilterBadInput, NoLightsGiveZerosAndAWarning)
{
  auto filter = FloorFilter();
  filter->RemoveAllLights();
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.HasWarning("no lights"));
  for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
  {
    EXPECT_TRUE(AllZero(filter->GetOutput(), name)) << name;
  }
}

TEST(GlobalIlluminationFilterBadInput, AlbedoAboveOneIsClampedOrRejected)
{
  auto filter = FloorFilter();
  filter->SetAlbedo(2.0, 0.5, 0.5);
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("Clamped the albedo"));
  EXPECT_NEAR(Value(filter->GetOutput(), "Radiance", 0, 0) * 3.14159265358979, 1.0, 1e-5);

  filter->ClampAlbedoOff();
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("albedo above 1"));

  filter->ClampAlbedoOn();
  filter->SetAlbedo(-0.5, 0.5, 0.5);
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("negative"));
}

TEST(GlobalIlluminationFilterBadInput, MissingArraysAreNamed)
{
  auto filter = FloorFilter();
  filter->SetAlbedoArrayName("NoSuchAlbedo");
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasError("'NoSuchAlbedo'"));

  filter->SetAlbedoArrayName(nullptr);
  filter->SetEmissionArrayName("NoSuchEmission");
  filter->SetEmissionArrayAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("'NoSuchEmission'"));
  EXPECT_TRUE(messages.HasError("cell data"));

  vtkNew<vtkFloatArray> tooShort; // one tuple for 25 points
  tooShort->SetName("TooShort");
  tooShort->InsertNextValue(0.5f);
  vtkSmartPointer<vtkPolyData> input = WithOwnPoints(MakeFloor(1, 4));
  input->GetPointData()->AddArray(tooShort);
  filter->SetInputData(input);
  filter->SetEmissionArrayName(nullptr);
  filter->SetAlbedoArrayName("TooShort");
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("'TooShort' has 1 tuples, but the input has 25 points"));
}

TEST(GlobalIlluminationFilterBadInput, InputWithoutNormalsGetsComputedNormals)
{
  vtkSmartPointer<vtkPolyData> withNormals = MakeFloor(1, 4);
  vtkSmartPointer<vtkPolyData> without = WithOwnPoints(withNormals);
  without->GetPointData()->SetNormals(nullptr);
  auto a = FloorFilter(withNormals);
  auto b = FloorFilter(without);
  MessageCapture messages(b);
  a->Update();
  b->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_EQ(Stat(b->GetOutput(), "Elements"), Stat(a->GetOutput(), "Elements"));
  for (vtkIdType i = 0; i < without->GetNumberOfPoints(); ++i)
  {
    EXPECT_NEAR(Value(b->GetOutput(), "DirectIrradiance", i), Value(a->GetOutput(), "DirectIrradiance", i), 1e-5);
  }
}

TEST(GlobalIlluminationFilterBadInput, LightsWithoutADirectionAreSkippedWithAWarning)
{
  // As the mapper does (both read lights with vtkGlobalIlluminationLights): the other
  // lights still shine.
  auto filter = FloorFilter();
  MessageCapture messages(filter);
  auto spot = MakeLight(Origin, Origin, 1.0, true, 20.0); // position == focal point
  auto sun = MakeLight(Origin, Origin, 1.0, false);
  filter->AddLight(spot);
  filter->AddLight(sun);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.HasWarning("spot light"));
  EXPECT_TRUE(messages.HasWarning("directional light"));
  EXPECT_TRUE(messages.HasWarning("no direction and is skipped"));
  EXPECT_NEAR(Value(filter->GetOutput(), "DirectIrradiance", 0), 1.0, 1e-4) << "the sun alone";
}

TEST(GlobalIlluminationFilterBadInput, BadTexturesAreErrors)
{
  auto filter = FloorFilter();
  MessageCapture messages(filter);

  vtkNew<vtkImageData> volume; // a 3D image is no lat-long map
  volume->SetDimensions(4, 2, 2);
  volume->AllocateScalars(VTK_FLOAT, 3);
  filter->SetEnvironmentColor(1, 1, 1);
  filter->SetEnvironmentTexture(volume);
  filter->Update();
  EXPECT_TRUE(messages.HasError("2D image"));
}

TEST(GlobalIlluminationFilterBadInput, AbortKeepsThePreviousOutput)
{
  auto filter = FloorFilter();
  vtkLight* sun = filter->GetLight(0);
  vtkNew<vtkCallbackCommand> abort; // what a GUI's cancel button does
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  MessageCapture messages(filter);

  unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, abort);
  filter->Update(); // aborted before any result: an empty output
  EXPECT_TRUE(messages.HasWarning("aborted"));
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  filter->RemoveObserver(tag);

  filter->Modified(); // VTK < 9.3 does not re-execute an aborted filter by itself
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  ASSERT_NEAR(Value(out, "DirectIrradiance", 0), 1.0, 1e-4);
  EXPECT_EQ(Stat(out, "LightLinkBuilds"), 1.0);

  sun->SetIntensity(2.0);
  tag = filter->AddObserver(vtkCommand::ProgressEvent, abort);
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("aborted"));
  EXPECT_NEAR(Value(out, "DirectIrradiance", 0), 1.0, 1e-4) << "the previous result";
  EXPECT_EQ(Stat(out, "LightLinkBuilds"), 1.0);
  filter->RemoveObserver(tag);

  sun->SetIntensity(3.0);
  filter->Update();
  EXPECT_NEAR(Value(out, "DirectIrradiance", 0), 3.0, 3e-4);
  EXPECT_EQ(Stat(out, "LightLinkBuilds"), 2.0);
  EXPECT_EQ(Stat(out, "LinkBuilds"), 1.0) << "an abort leaves the engine's caches intact";
}

TEST(GlobalIlluminationFilterBadInput, ColourArraysOfTheWrongShapeAreErrorsNamingThemAndKeepThePreviousOutput)
{
  vtkSmartPointer<vtkPolyData> input = WithOwnPoints(MakeFloor(1, 4));
  auto filter = FloorFilter(input);
  filter->Update();
  const double before = Value(filter->GetOutput(), "DirectIrradiance", 3);
  ASSERT_NEAR(before, 1.0, 1e-4);

  vtkNew<vtkFloatArray> twoComponents; // e.g. luminance + alpha, or a 2D vector field
  twoComponents->SetName("Glow");
  twoComponents->SetNumberOfComponents(2);
  twoComponents->SetNumberOfTuples(input->GetNumberOfPoints());
  twoComponents->Fill(0.5);
  input->GetPointData()->AddArray(twoComponents);
  filter->SetEmissionArrayName("Glow");
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasError("The emission array 'Glow' has 2 components"));
  EXPECT_EQ(Value(filter->GetOutput(), "DirectIrradiance", 3), before) << "the previous output is kept";

  filter->SetEmissionArrayName(nullptr);
  vtkNew<vtkStringArray> names;
  names->SetName("Names");
  names->SetNumberOfTuples(input->GetNumberOfPoints());
  input->GetPointData()->AddArray(names);
  filter->SetAlbedoArrayName("Names");
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.HasError("The albedo array 'Names' is not a numeric array"));
  EXPECT_EQ(Value(filter->GetOutput(), "DirectIrradiance", 3), before);

  // Four components (RGBA) are a colour.
  vtkNew<vtkFloatArray> rgba;
  rgba->SetName("RGBA");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(input->GetNumberOfPoints());
  rgba->Fill(0.5);
  input->GetPointData()->AddArray(rgba);
  filter->SetAlbedoArrayName("RGBA");
  messages.Clear();
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
}

TEST(GlobalIlluminationFilterBadInput, RoundedRaysPerVertexIsInTheOutputsWarnings)
{
  auto filter = FloorFilter(WithOwnPoints(MakeFloor(1, 4)));
  const auto warnings = [&filter] {
    auto* list = vtkStringArray::SafeDownCast(
      filter->GetOutput()->GetFieldData()->GetAbstractArray("LinkGI.Warnings"));
    std::string all;
    for (vtkIdType i = 0; list && i < list->GetNumberOfValues(); ++i)
    {
      all += list->GetValue(i) + "\n";
    }
    return all;
  };
  MessageCapture messages(filter);
  filter->SetRaysPerVertex(7);
  EXPECT_EQ(filter->GetRaysPerVertex(), 9);
  filter->Update();
  EXPECT_NE(warnings().find("using 9 instead of 7"), std::string::npos);
  filter->SetNumberOfBounces(2); // a later update still says it
  filter->Update();
  EXPECT_NE(warnings().find("using 9 instead of 7"), std::string::npos);
  filter->SetRaysPerVertex(16); // a valid value clears it
  filter->Update();
  EXPECT_EQ(warnings().find("perfect square"), std::string::npos);
  EXPECT_TRUE(messages.Errors.empty());
}

TEST(GlobalIlluminationFilterBadInput, ASphereScaledBy1e30IsLitAsTheUnitSphere)
{
  // The edge case: the sphere scaled by 1e30 lost 69 of its 96 triangles as "degenerate"
  // (float overflow in the area test). Under the sun (irradiance does not depend on the
  // distance) it must keep every triangle and get the unit sphere's light.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(12);
  sphere->SetPhiResolution(10);
  sphere->Update();
  vtkNew<vtkTransform> scale;
  scale->Scale(1e30, 1e30, 1e30);
  vtkNew<vtkTransformPolyDataFilter> huge;
  huge->SetInputConnection(sphere->GetOutputPort());
  huge->SetTransform(scale);
  huge->Update();
  ASSERT_EQ(huge->GetOutput()->GetNumberOfCells(), sphere->GetOutput()->GetNumberOfCells());

  const auto lit = [](vtkPolyData* input) {
    auto filter = FloorFilter(input);
    MessageCapture messages(filter);
    filter->Update();
    EXPECT_FALSE(messages.HasWarning("degenerate")) << "no triangle is lost to the scale";
    EXPECT_TRUE(messages.Errors.empty());
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->DeepCopy(filter->GetOutput());
    return out;
  };
  const auto unit = lit(sphere->GetOutput());
  const auto big = lit(huge->GetOutput());
  vtkDataArray* a = PointArray(unit, "DirectIrradiance");
  vtkDataArray* b = PointArray(big, "DirectIrradiance");
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  double worst = 0.0, largest = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::abs(a->GetComponent(i, 0) - b->GetComponent(i, 0)));
    largest = std::max(largest, a->GetComponent(i, 0));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(worst, 1e-4 * largest) << "the scale changes no result";
}
