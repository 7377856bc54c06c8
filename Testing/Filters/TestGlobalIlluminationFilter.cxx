// vtkGlobalIlluminationFilter: output layout, agreement with the engine, cell types, albedo
// sources, light conversion and analytic irradiance (incremental updates:
// TestGlobalIlluminationFilterUpdates.cxx).
#include "FilterTestUtilities.h"

#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkImageData.h"
#include "vtkLightCollection.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

using namespace linkgi_test;

namespace
{
const double Origin[3] = { 0, 0, 0 };
}

TEST(GlobalIlluminationFilter, OutputIsTheInputGeometryWithFloatArraysAndCounters)
{
  vtkSmartPointer<vtkPolyData> input = MakeSphereOnFloor();
  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkFloatArray> temperature; // a user's array that must survive
  temperature->SetName("Temperature");
  temperature->SetNumberOfTuples(n);
  temperature->Fill(42.0);
  input->GetPointData()->AddArray(temperature);

  auto filter = MakeFilter(input);
  const double lamp[3] = { 0.5, 0.5, 4 };
  filter->AddLight(MakeLight(lamp, Origin, 16));
  filter->Update();
  vtkPolyData* out = filter->GetOutput();

  EXPECT_EQ(out->GetPoints(), input->GetPoints()); // a shallow copy
  EXPECT_EQ(out->GetNumberOfPolys(), input->GetNumberOfPolys());
  EXPECT_EQ(PointArray(out, "Temperature"), temperature.GetPointer());
  for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
  {
    vtkDataArray* array = PointArray(out, name);
    ASSERT_NE(array, nullptr) << name;
    EXPECT_EQ(array->GetDataType(), VTK_FLOAT) << name;
    EXPECT_EQ(array->GetNumberOfComponents(), 3) << name;
    EXPECT_EQ(array->GetNumberOfTuples(), n) << name;
    for (int c = 0; c < 3; ++c)
    {
      const double* range = array->GetRange(c);
      EXPECT_GE(range[0], 0.0) << name;
      EXPECT_TRUE(std::isfinite(range[1])) << name;
    }
    EXPECT_EQ(PointArray(input, name), nullptr) << "the input must stay untouched";
  }
  EXPECT_GT(PointArray(out, "DirectIrradiance")->GetRange(0)[1], 0.5);
  EXPECT_GT(PointArray(out, "IndirectIrradiance")->GetRange(0)[1], 0.0);

  EXPECT_EQ(Stat(out, "Elements"), n); // sources' normals: no split vertices
  EXPECT_GT(Stat(out, "Rays"), 0);
  EXPECT_GT(Stat(out, "LinksCompressed"), 0);
  EXPECT_GE(Stat(out, "LinksRaw"), Stat(out, "LinksCompressed"));
  EXPECT_GT(Stat(out, "LinkBytes"), 0);
  for (const char* counter : { "BvhBuilds", "LinkBuilds", "LightLinkBuilds", "BounceRuns" })
  {
    EXPECT_EQ(Stat(out, counter), 1.0) << counter;
  }
  EXPECT_EQ(Stat(out, "BvhRefits"), 0.0);
  EXPECT_GT(Stat(out, "MsTotal"), 0.0);
  EXPECT_GE(Stat(out, "MsFilter"), Stat(out, "MsTotal"));
  EXPECT_NE(vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("LinkGI.Warnings")), nullptr);
  EXPECT_EQ(input->GetFieldData()->GetAbstractArray("LinkGI.Elements"), nullptr);
}

TEST(GlobalIlluminationFilter, AgreesWithTheEngineOnTheCornellBox)
{
  const linkgi::Scene scene = linkgi::makeStandardScene("cornell");
  vtkSmartPointer<vtkPolyData> input = ToPolyData(scene);
  auto filter = MakeFilter(input, 64);
  filter->SetAlbedoArrayName("Albedo");
  if (!scene.emission.empty())
  {
    filter->SetEmissionArrayName("Emission");
  }
  for (const linkgi::Light& light : scene.lights)
  {
    filter->AddLight(ToVtkLight(light));
  }
  const linkgi::Vec3f& sky = scene.environment.color;
  filter->SetEnvironmentColor(sky.x, sky.y, sky.z);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();

  // The filter solves relative to the centre of the surface's bounds (in double precision).
  linkgi::Scene local = scene;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const linkgi::Vec3f& p : scene.positions)
  {
    const double x[3] = { p.x, p.y, p.z };
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], x[k]);
      hi[k] = std::max(hi[k], x[k]);
    }
  }
  const auto toLocal = [&](linkgi::Vec3f& p) {
    p = { float(p.x - 0.5 * (lo[0] + hi[0])), float(p.y - 0.5 * (lo[1] + hi[1])),
      float(p.z - 0.5 * (lo[2] + hi[2])) };
  };
  std::for_each(local.positions.begin(), local.positions.end(), toLocal);
  for (linkgi::Light& light : local.lights)
  {
    toLocal(light.position);
  }
  linkgi::SolverOptions options;
  options.raysPerVertex = 64;
  linkgi::Solver solver;
  const linkgi::Solution& reference = solver.update(local, options);
  ASSERT_EQ(Stat(out, "Elements"), static_cast<double>(reference.elementCount()));
  const std::pair<const char*, const std::vector<linkgi::Vec3f>*> arrays[] = {
    { "DirectIrradiance", &reference.direct }, { "IndirectIrradiance", &reference.indirect },
    { "Radiance", &reference.radiance }
  };
  for (const auto& a : arrays)
  {
    vtkSmartPointer<vtkFloatArray> expected = ToArray(*a.second, a.first);
    EXPECT_LT(RelativeDifference(PointArray(out, a.first), expected), 1e-5) << a.first;
  }
  EXPECT_GT(PointArray(out, "IndirectIrradiance")->GetRange(1)[1], 0.0);
}

TEST(GlobalIlluminationFilter, PolygonsAndStripsAreLitLinesAndVerticesPassThrough)
{
  vtkNew<vtkPoints> points;
  const double coords[][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, // quad
    { 0, 2, 0 }, { 1, 2, 0 }, { 0, 3, 0 }, { 1, 3, 0 }, { 0, 4, 0 },                 // strip
    { 3, 0, 0.5 }, { 3, 1, 0.5 },                                                    // line
    { 3, 3, 0.5 } };                                                                 // vertex
  for (const auto& p : coords)
  {
    points->InsertNextPoint(p);
  }
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  vtkNew<vtkCellArray> polys, strips, lines, verts;
  const vtkIdType quad[] = { 0, 1, 2, 3 }, strip[] = { 4, 5, 6, 7, 8 }, line[] = { 9, 10 },
                  vert[] = { 11 };
  polys->InsertNextCell(4, quad);
  strips->InsertNextCell(5, strip);
  lines->InsertNextCell(2, line);
  verts->InsertNextCell(1, vert);
  input->SetPolys(polys);
  input->SetStrips(strips);
  input->SetLines(lines);
  input->SetVerts(verts);

  auto filter = MakeFilter(input);
  filter->AddLight(Sun(1.0));
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(out->GetNumberOfLines(), 1);
  EXPECT_EQ(out->GetNumberOfVerts(), 1);
  EXPECT_EQ(out->GetNumberOfStrips(), 1);
  EXPECT_EQ(out->GetNumberOfPolys(), 1);
  ASSERT_EQ(PointArray(out, "DirectIrradiance")->GetNumberOfTuples(), 12);
  EXPECT_EQ(Stat(out, "Elements"), 9.0); // the points of lines and vertices are no elements
  for (vtkIdType i = 0; i < 9; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(Value(out, "DirectIrradiance", i, c), 1.0, 1e-4) << "point " << i;
    }
  }
  for (vtkIdType i = 9; i < 12; ++i)
  {
    for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
    {
      EXPECT_EQ(Value(out, name, i), 0.0) << name << " of unlit point " << i;
    }
  }
}

TEST(GlobalIlluminationFilter, SplitVerticesAverageTheirCopies)
{
  // A cube without normals: each corner is split into three copies, one per face. Sun from
  // straight above: the top face copies get 1, the side copies 0, so a top corner gets 1/3.
  vtkSmartPointer<vtkPolyData> cube = MakeCube();
  auto filter = MakeFilter(cube);
  filter->AddLight(Sun(1.0));
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(Stat(out, "Elements"), 24.0);
  ASSERT_EQ(PointArray(out, "DirectIrradiance")->GetNumberOfTuples(), 8);
  for (vtkIdType i = 0; i < 8; ++i)
  {
    const bool top = cube->GetPoint(i)[2] > 0.5;
    EXPECT_NEAR(Value(out, "DirectIrradiance", i), top ? 1.0 / 3.0 : 0.0, 1e-4) << "corner " << i;
  }
  EXPECT_EQ(out->GetPointData()->GetNormals(), nullptr) << "computed normals are not output";
}

TEST(GlobalIlluminationFilter, PointAndCellAlbedoAgreeAndColourArraysConvert)
{
  vtkSmartPointer<vtkPolyData> floor = MakeFloor(1, 4);
  const float rho[3] = { 0.5f, 0.25f, 0.1f };
  vtkNew<vtkFloatArray> pointAlbedo, cellAlbedo, grey;
  vtkNew<vtkUnsignedCharArray> bytes;
  pointAlbedo->SetName("PointAlbedo");
  cellAlbedo->SetName("CellAlbedo");
  grey->SetName("Grey");
  bytes->SetName("Bytes");
  for (auto* array : { static_cast<vtkDataArray*>(pointAlbedo), static_cast<vtkDataArray*>(cellAlbedo),
         static_cast<vtkDataArray*>(bytes) })
  {
    array->SetNumberOfComponents(array == bytes.GetPointer() ? 4 : 3); // RGBA: alpha ignored
  }
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    pointAlbedo->InsertNextTypedTuple(rho);
    grey->InsertNextValue(0.4f);
    const unsigned char rgba[4] = { 255, 51, 0, 7 };
    bytes->InsertNextTypedTuple(rgba);
  }
  for (vtkIdType i = 0; i < floor->GetNumberOfCells(); ++i)
  {
    cellAlbedo->InsertNextTypedTuple(rho);
  }
  floor->GetPointData()->AddArray(pointAlbedo);
  floor->GetPointData()->AddArray(grey);
  floor->GetPointData()->AddArray(bytes);
  floor->GetCellData()->AddArray(cellAlbedo);

  auto run = [&](const char* name, int association) {
    auto filter = MakeFilter(floor);
    filter->AddLight(Sun(1.0));
    filter->SetAlbedoArrayName(name);
    filter->SetAlbedoArrayAssociation(association);
    filter->Update();
    vtkSmartPointer<vtkPolyData> out = filter->GetOutput();
    return out;
  };
  // A lone floor under the sun: E = 1 and nothing to bounce off, so L = rho / pi.
  auto points = run("PointAlbedo", vtkDataObject::FIELD_ASSOCIATION_POINTS);
  auto cells = run("CellAlbedo", vtkDataObject::FIELD_ASSOCIATION_CELLS);
  auto greys = run("Grey", vtkDataObject::FIELD_ASSOCIATION_POINTS);
  auto rgba = run("Bytes", vtkDataObject::FIELD_ASSOCIATION_POINTS);
  const double pi = 3.14159265358979;
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(Value(points, "Radiance", i, c), rho[c] / pi, 1e-5);
      EXPECT_NEAR(Value(cells, "Radiance", i, c), rho[c] / pi, 1e-5);
      EXPECT_NEAR(Value(greys, "Radiance", i, c), 0.4 / pi, 1e-5);
      // Bytes are display colours: 51 / 255 is 0.0331 in linear light.
      EXPECT_NEAR(Value(rgba, "Radiance", i, c), (c == 0 ? 1.0 : c == 1 ? 0.0331 : 0.0) / pi, 1e-5);
    }
  }
}

TEST(GlobalIlluminationFilter, CellAlbedoIsAveragedOverAPointsCells)
{
  vtkNew<vtkPlaneSource> plane; // two cells side by side: albedo 0.2 | 0.8
  plane->SetOrigin(0, 0, 0);
  plane->SetPoint1(2, 0, 0);
  plane->SetPoint2(0, 1, 0);
  plane->SetResolution(2, 1);
  plane->Update();
  vtkPolyData* input = plane->GetOutput();
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->InsertNextValue(0.2f);
  albedo->InsertNextValue(0.8f);
  input->GetCellData()->AddArray(albedo);
  auto filter = MakeFilter(input);
  filter->AddLight(Sun(1.0));
  filter->SetAlbedoArrayName("Albedo");
  filter->SetAlbedoArrayAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  const double pi = 3.14159265358979;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const double x = out->GetPoint(i)[0];
    // Corner points touch one triangle of their cell; middle points triangles of both cells.
    const double expected = x < 0.5 ? 0.2 : (x > 1.5 ? 0.8 : -1.0);
    if (expected > 0)
    {
      EXPECT_NEAR(Value(out, "Radiance", i) * pi, expected, 1e-5) << "point " << i;
    }
    else
    {
      const double mid = Value(out, "Radiance", i) * pi;
      EXPECT_GT(mid, 0.2 + 1e-3);
      EXPECT_LT(mid, 0.8 - 1e-3);
    }
  }
}

TEST(GlobalIlluminationFilter, PointSpotAndDirectionalLightsFollowTheirUnits)
{
  vtkSmartPointer<vtkPolyData> floor = MakeFloor(2, 8);
  const double lamp[3] = { 0, 0, 2 };
  auto check = [&](vtkLight* light, double scale, const auto& expected) {
    auto filter = MakeFilter(floor);
    filter->AddLight(light);
    filter->SetLightIntensityScale(scale);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      const double* p = out->GetPoint(i);
      const double e = expected(p);
      if (std::isnan(e))
      {
        continue; // too close to a spot light's cone edge to say
      }
      EXPECT_NEAR(Value(out, "DirectIrradiance", i), e, 1e-4 * std::max(1.0, e))
        << "point " << p[0] << ", " << p[1];
    }
  };
  // Point light, I = 4 W/sr, 2 m up: E = I cos(theta) / r^2 = I h / r^3.
  auto pointLight = MakeLight(lamp, Origin, 4);
  check(pointLight, 1.0, [](const double* p) {
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + 4.0);
    return 4.0 * 2.0 / (r * r * r);
  });
  // LightIntensityScale multiplies, and the light's colour is per channel.
  check(pointLight, 3.0, [](const double* p) {
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + 4.0);
    return 12.0 * 2.0 / (r * r * r);
  });
  // Spot light with a 30 degree half angle (hard cone): points outside the cone get 0.
  auto spot = MakeLight(lamp, Origin, 4, true, 30);
  check(spot, 1.0, [](const double* p) {
    const double d = std::sqrt(p[0] * p[0] + p[1] * p[1]);
    const double angle = std::atan2(d, 2.0) * 180.0 / 3.14159265358979;
    const double r = std::sqrt(d * d + 4.0);
    return std::abs(angle - 30.0) < 1.0 ? std::nan("") : (angle < 30.0 ? 8.0 / (r * r * r) : 0.0);
  });
  // Directional light at 60 degrees from the normal: E = cos(60) = 0.5 everywhere.
  const double slanted[3] = { std::sqrt(3.0), 0, 1 };
  check(MakeLight(slanted, Origin, 1, false), 1.0, [](const double*) { return 0.5; });
  // A switched-off light does not count.
  auto off = MakeLight(lamp, Origin, 4);
  off->SwitchOff();
  check(off, 1.0, [](const double*) { return 0.0; });
}

TEST(GlobalIlluminationFilter, UniformSkyGivesPiTimesItsRadiance)
{
  // An open plane facing up (+Y, the environment's up) under a sky of radiance L sees only
  // sky: E = pi L, whatever the number of rays.
  const double o[3] = { -1, 0, 1 }, p1[3] = { 1, 0, 1 }, p2[3] = { -1, 0, -1 };
  vtkSmartPointer<vtkPolyData> plane = MakePlane(o, p1, p2, 6);
  auto filter = MakeFilter(plane);
  filter->SetEnvironmentColor(1.0, 0.5, 0.25);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  const double pi = 3.14159265358979;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    EXPECT_NEAR(Value(out, "IndirectIrradiance", i, 0), pi, 1e-4);
    EXPECT_NEAR(Value(out, "IndirectIrradiance", i, 1), pi * 0.5, 1e-4);
    EXPECT_NEAR(Value(out, "IndirectIrradiance", i, 2), pi * 0.25, 1e-4);
    EXPECT_EQ(Value(out, "DirectIrradiance", i), 0.0);
  }

  // A lat-long map: bright upper half (the image's top row), black lower half, times the
  // colour. The up-facing plane sees only the upper half: E = pi again.
  vtkNew<vtkImageData> sky;
  sky->SetDimensions(4, 2, 1);
  sky->AllocateScalars(VTK_FLOAT, 3);
  auto* texels = vtkFloatArray::SafeDownCast(sky->GetPointData()->GetScalars());
  for (vtkIdType j = 0; j < 2; ++j)
  {
    for (vtkIdType i = 0; i < 4; ++i)
    {
      const float v = j == 1 ? 1.f : 0.f;
      const float rgb[3] = { v, v, v };
      texels->SetTypedTuple(j * 4 + i, rgb);
    }
  }
  filter->SetEnvironmentColor(1, 1, 1);
  filter->SetEnvironmentTexture(sky);
  filter->Update();
  EXPECT_NEAR(Value(out, "IndirectIrradiance", 0, 0), pi, 1e-4);
  // Turned upside down (MTime of the texture counts): the plane sees black.
  for (vtkIdType i = 0; i < 8; ++i)
  {
    const float v = i < 4 ? 1.f : 0.f;
    const float rgb[3] = { v, v, v };
    texels->SetTypedTuple(i, rgb);
  }
  texels->Modified();
  filter->Update();
  EXPECT_NEAR(Value(out, "IndirectIrradiance", 0, 0), 0.0, 1e-6);
  EXPECT_EQ(Stat(out, "LinkBuilds"), 2.0) << "a new texture layout relinks, recolouring does not";
}

TEST(GlobalIlluminationFilter, TwoSidedAddsBackArrays)
{
  auto filter = MakeFilter(MakeFloor(1, 4));
  const double below[3] = { 0, 0, -1 };
  filter->AddLight(MakeLight(below, Origin, 1, false)); // travels up: lights the back
  filter->TwoSidedOn();
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  ASSERT_NE(PointArray(out, "DirectIrradianceBack"), nullptr);
  ASSERT_NE(PointArray(out, "RadianceBack"), nullptr);
  EXPECT_EQ(Stat(out, "Elements"), 2.0 * out->GetNumberOfPoints());
  EXPECT_NEAR(Value(out, "DirectIrradianceBack", 0), 1.0, 1e-4);
  EXPECT_EQ(Value(out, "DirectIrradiance", 0), 0.0);
  filter->TwoSidedOff();
  filter->Update();
  EXPECT_EQ(PointArray(out, "DirectIrradianceBack"), nullptr);
}

TEST(GlobalIlluminationFilter, LightsFromARendererAreTheSameObjects)
{
  vtkNew<vtkRenderer> renderer;
  ASSERT_NE(renderer.GetPointer(), nullptr);
  const double lamp[3] = { 0, 0, 2 };
  auto a = MakeLight(lamp, Origin, 4);
  auto b = Sun(1.0);
  renderer->AddLight(a);
  renderer->AddLight(b);
  vtkNew<vtkGlobalIlluminationFilter> filter;
  filter->AddLight(Sun(2.0));
  filter->SetLightsFromRenderer(renderer);
  ASSERT_EQ(filter->GetNumberOfLights(), 2);
  EXPECT_EQ(filter->GetLight(0), a.GetPointer());
  EXPECT_EQ(filter->GetLight(1), b.GetPointer());
  const vtkMTimeType before = filter->GetMTime();
  filter->SetLightsFromRenderer(renderer); // the same lights: not modified
  EXPECT_EQ(filter->GetMTime(), before);
  b->SetIntensity(3.0);
  EXPECT_GT(filter->GetMTime(), before);
  filter->RemoveLight(a);
  EXPECT_EQ(filter->GetNumberOfLights(), 1);
  filter->RemoveAllLights();
  EXPECT_EQ(filter->GetNumberOfLights(), 0);
}

TEST(GlobalIlluminationFilter, PropertiesHaveTheirDocumentedDefaults)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  EXPECT_EQ(filter->GetRaysPerVertex(), 256);
  EXPECT_EQ(filter->GetNumberOfBounces(), 3);
  EXPECT_EQ(filter->GetFeatureAngle(), 30.0);
  EXPECT_FALSE(filter->GetSmoothing());
  EXPECT_EQ(filter->GetVPLCompensationRays(), 64);
  EXPECT_FALSE(filter->GetComputeNormals());
  EXPECT_EQ(filter->GetBackend(), vtkGlobalIlluminationFilter::AUTO);
  EXPECT_EQ(filter->GetAlbedoArrayName(), nullptr);
  EXPECT_EQ(filter->GetAlbedoArrayAssociation(), vtkDataObject::FIELD_ASSOCIATION_POINTS);
  EXPECT_EQ(filter->GetAlbedo()[0], 0.7);
  EXPECT_TRUE(filter->GetClampAlbedo());
  EXPECT_EQ(filter->GetEnvironmentColor()[0], 0.0);
  EXPECT_EQ(filter->GetEnvironmentTexture(), nullptr);
  EXPECT_FALSE(filter->GetTwoSided());
  EXPECT_EQ(filter->GetSeed(), 0);
  EXPECT_TRUE(filter->GetLightOversampling());
  EXPECT_TRUE(filter->GetTwist());
  EXPECT_EQ(filter->GetLightIntensityScale(), 1.0);
  std::ostringstream print;
  filter->Print(print);
  EXPECT_NE(print.str().find("Rays Per Vertex: 256"), std::string::npos);
  EXPECT_NE(print.str().find("Backend: Auto"), std::string::npos);

  MessageCapture messages(filter);
  filter->SetRaysPerVertex(250); // rounded to the nearest perfect square
  EXPECT_EQ(filter->GetRaysPerVertex(), 256);
  EXPECT_TRUE(messages.HasWarning("perfect square"));
  filter->SetRaysPerVertex(17);
  EXPECT_EQ(filter->GetRaysPerVertex(), 16);
  filter->SetRaysPerVertex(0);
  EXPECT_EQ(filter->GetRaysPerVertex(), 1);
  filter->SetNumberOfBounces(-3);
  EXPECT_EQ(filter->GetNumberOfBounces(), 0);
  filter->SetFeatureAngle(500);
  EXPECT_EQ(filter->GetFeatureAngle(), 180.0);
}

// The filter's options start where the engine's do (SolverOptions holds the defaults).
TEST(GlobalIlluminationFilter, OptionDefaultsAreTheEngines)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  const linkgi::SolverOptions engine;
  EXPECT_EQ(filter->GetRaysPerVertex(), int(engine.raysPerVertex));
  EXPECT_EQ(filter->GetNumberOfBounces(), int(engine.bounces));
  EXPECT_EQ(filter->GetNumberOfVPLs(), int(engine.instantRadiosity.vplCount));
  EXPECT_EQ(float(filter->GetVPLClampDistance()), engine.instantRadiosity.clampDistance);
  EXPECT_EQ(filter->GetVPLInterleaving(), int(engine.instantRadiosity.interleave));
  EXPECT_EQ(filter->GetVPLCompensationRays(), int(engine.instantRadiosity.compensationRays));
  EXPECT_EQ(filter->GetProxyVisibility() != 0, engine.instantRadiosity.proxyVisibility);
  EXPECT_EQ(filter->GetProxyResolution(), int(engine.instantRadiosity.proxyResolution));
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), int(engine.implicitVisibility.binsPerSide));
  EXPECT_EQ(filter->GetNumberOfPhotons(), int(engine.photonMapping.photons));
  EXPECT_EQ(filter->GetNumberOfClusters(), int(engine.photonMapping.clusters));
  EXPECT_EQ(filter->GetFinalGatherRays(), int(engine.photonMapping.gatherRays));
  EXPECT_EQ(filter->GetReferencePathsPerVertex(), int(engine.reference.pathsPerVertex));
  EXPECT_EQ(filter->GetFeatureAngle(), double(engine.featureAngleDegrees));
  EXPECT_EQ(filter->GetSmoothing() != 0, engine.smoothing);
  EXPECT_EQ(filter->GetTwoSided() != 0, engine.twoSided);
  EXPECT_EQ(filter->GetSeed(), int(engine.seed));
  EXPECT_EQ(filter->GetLightOversampling() != 0, engine.lightOversampling);
  EXPECT_EQ(filter->GetTwist() != 0, engine.twist);
}

TEST(GlobalIlluminationFilter, CudaRequestFallsBackToTheCpuWithAWarning)
{
  auto filter = MakeFilter(MakeFloor(1, 4));
  filter->AddLight(Sun(1.0));
  filter->SetBackendToCUDA();
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("CUDA backend not available in this build; using the CPU"));
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_NEAR(Value(filter->GetOutput(), "DirectIrradiance", 0), 1.0, 1e-4);
  auto* warnings = vtkStringArray::SafeDownCast(
    filter->GetOutput()->GetFieldData()->GetAbstractArray("LinkGI.Warnings"));
  ASSERT_NE(warnings, nullptr);
  ASSERT_GE(warnings->GetNumberOfValues(), 1);
  EXPECT_NE(warnings->GetValue(0).find("CUDA"), std::string::npos);
}
