// Real data as it comes: the Stanford bunny as its PLY file ships (wound inward, with holes;
// Testing/Data/Models/README.md), surfaces lit from behind, coordinates far from the origin
// and lengths in millimetres or kilometres. None of it may give a silent wrong answer.
#include "FilterTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkPolyDataNormals.h"
#include "vtkReverseSense.h"
#include "vtkStringArray.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkXMLPolyDataReader.h"

#include "linkgi/Memory.h"
#include "linkgi/Resolution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

using namespace linkgi_test;

namespace
{
/// Whether `method` decides each direction bin's source by a ray against a triangle's edge
/// (implicit visibility's near leaves), where float rounding can move a whole bin.
bool DiscreteBins(int method)
{
  return method == vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY;
}

const int Methods[] = { vtkGlobalIlluminationFilter::LINKS,
  vtkGlobalIlluminationFilter::INSTANT_RADIOSITY, vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY,
  vtkGlobalIlluminationFilter::PHOTON_MAPPING };
const char* const Arrays[] = { "DirectIrradiance", "IndirectIrradiance", "Radiance" };

/// The bunny (1,573 points, 0.15 m tall) as stored: its triangles wound inward.
vtkSmartPointer<vtkPolyData> InwardBunny()
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(LINKGI_TEST_MODELS_DIR "/bunny-inward.vtp");
  reader->Update();
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> Reversed(vtkPolyData* input)
{
  vtkNew<vtkReverseSense> reverse;
  reverse->SetInputData(input);
  reverse->ReverseCellsOn();
  reverse->ReverseNormalsOn();
  reverse->Update();
  return reverse->GetOutput();
}

/// `input` scaled by `scale` about the origin, then moved by `offset`, in double precision.
vtkSmartPointer<vtkPolyData> Placed(vtkPolyData* input, double scale, const double offset[3])
{
  vtkNew<vtkTransform> transform;
  transform->Translate(offset);
  transform->Scale(scale, scale, scale);
  vtkNew<vtkTransformPolyDataFilter> move;
  move->SetInputData(input);
  move->SetTransform(transform);
  move->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  move->Update();
  return move->GetOutput();
}

/// The bunny (outward) on a floor, a point light above and to the side, placed as above.
/// The light's intensity grows with scale^2 so that the irradiance stays the same.
vtkSmartPointer<vtkPolyData> LitBunnyOnFloor(int method, double scale, const double offset[3],
  std::vector<std::string>* warnings = nullptr)
{
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(Reversed(InwardBunny()));
  const double o[3] = { -0.2, 0.033, -0.2 }, p1[3] = { -0.2, 0.033, 0.2 }, p2[3] = { 0.2, 0.033, -0.2 };
  append->AddInputData(MakePlane(o, p1, p2, 16)); // y = 0.033 (the bunny's feet), facing +y
  append->Update();
  vtkNew<vtkGlobalIlluminationFilter> filter;
  filter->SetInputData(Placed(append->GetOutput(), scale, offset));
  const double light[3] = { scale * 0.15 + offset[0], scale * 0.35 + offset[1], scale * 0.2 + offset[2] };
  filter->AddLight(MakeLight(light, offset, 0.05 * scale * scale));
  filter->SetMethod(method);
  filter->SetBackendToCPU();
  filter->SetRaysPerVertex(64);
  filter->SetNumberOfBounces(2);
  filter->Update();
  if (warnings)
  {
    *warnings = Warnings(filter->GetOutput());
  }
  return filter->GetOutput();
}

/// How far an array of one result is from another's: the largest difference and the root
/// mean square difference, both relative to the largest value of `a`.
struct Difference
{
  double Largest = 0.0, Rms = 0.0;
};

Difference Compare(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  vtkDataArray* x = PointArray(a, name);
  vtkDataArray* y = PointArray(b, name);
  EXPECT_EQ(x->GetNumberOfValues(), y->GetNumberOfValues());
  double largest = 0.0, maxDifference = 0.0, squares = 0.0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    const int nc = x->GetNumberOfComponents();
    const double a = x->GetComponent(i / nc, int(i % nc)), b = y->GetComponent(i / nc, int(i % nc));
    const double d = a - b;
    largest = std::max(largest, std::abs(a));
    maxDifference = std::max(maxDifference, std::abs(d));
    squares += d * d;
  }
  EXPECT_GT(largest, 0.0) << name;
  const double rms = std::sqrt(squares / double(std::max<vtkIdType>(x->GetNumberOfValues(), 1)));
  return { maxDifference / largest, rms / largest };
}

double LitFraction(vtkPolyData* pd)
{
  vtkDataArray* direct = PointArray(pd, "DirectIrradiance");
  vtkIdType lit = 0;
  for (vtkIdType i = 0; i < direct->GetNumberOfTuples(); ++i)
  {
    lit += direct->GetComponent(i, 0) > 0.0 ? 1 : 0;
  }
  return double(lit) / double(direct->GetNumberOfTuples());
}
}

TEST(TestGlobalIlluminationRealData, InwardBunnyIsLitFromOutsideWithAWarning)
{
  const vtkSmartPointer<vtkPolyData> inward = InwardBunny();
  const vtkSmartPointer<vtkPolyData> outward = Reversed(inward);
  for (const int method : Methods)
  {
    vtkSmartPointer<vtkPolyData> results[2];
    std::vector<std::string> warnings[2];
    for (int i = 0; i < 2; ++i)
    {
      vtkNew<vtkGlobalIlluminationFilter> filter;
      filter->SetInputData(i == 0 ? inward : outward);
      const double light[3] = { 0.3, 0.4, 0.5 }, at[3] = { 0, 0.1, 0 };
      filter->AddLight(MakeLight(light, at, 0.05));
      filter->SetMethod(method);
      filter->SetBackendToCPU();
      filter->SetRaysPerVertex(64);
      filter->Update();
      results[i] = filter->GetOutput();
      warnings[i] = Warnings(results[i]);
    }
    EXPECT_TRUE(MessageCapture::Contains(warnings[0], "normals pointing inward")) << method;
    EXPECT_FALSE(MessageCapture::Contains(warnings[1], "normals pointing inward")) << method;
    EXPECT_GT(LitFraction(results[1]), 0.3) << method;
    for (const char* name : Arrays)
    {
      // Not bit for bit: the reversed cells list each triangle's points in the other order,
      // so sums run in another order (implicit visibility's clusters move most: 1.5e-3).
      const Difference d = Compare(results[1], results[0], name);
      EXPECT_LT(d.Largest, 1e-2) << method << ' ' << name;
      EXPECT_LT(d.Rms, 5e-4) << method << ' ' << name;
    }
  }
}

TEST(TestGlobalIlluminationRealData, AClosedSurfaceWithASeamIsLitFromOutside)
{
  // vtkTexturedSphereSource repeats its first meridian's points (their texture coordinates
  // differ), as the surface of a structured grid that wraps around repeats its seam; wound
  // inward, it is still a closed surface, lit from outside with a warning, as the same
  // sphere wound outward is lit without one.
  const double light[3] = { 2.0, 3.0, 4.0 }, at[3] = { 0, 0, 0 };
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkSmartPointer<vtkPolyData> outputs[2];
  std::vector<std::string> warnings[2];
  vtkSmartPointer<vtkPolyData> inputs[2] = { sphere->GetOutput(), Reversed(sphere->GetOutput()) };
  for (int i = 0; i < 2; ++i)
  {
    vtkNew<vtkGlobalIlluminationFilter> filter;
    filter->SetInputData(inputs[i]);
    filter->AddLight(MakeLight(light, at, 1.0));
    filter->SetBackendToCPU();
    filter->Update();
    outputs[i] = filter->GetOutput();
    warnings[i] = Warnings(outputs[i]);
  }
  EXPECT_FALSE(MessageCapture::Contains(warnings[0], "lit from outside"));
  EXPECT_FALSE(MessageCapture::Contains(warnings[0], "Shadows block"));
  EXPECT_TRUE(MessageCapture::Contains(warnings[1], "lit from outside"));
  EXPECT_GT(LitFraction(outputs[1]), 0.3);
  EXPECT_EQ(LitFraction(outputs[1]), LitFraction(outputs[0]));
}

TEST(TestGlobalIlluminationRealData, SurfaceLitOnlyFromBehindSaysHowToLightIt)
{
  const double light[3] = { 0.2, 0.1, -1.0 }, at[3] = { 0, 0, 0 };
  vtkNew<vtkGlobalIlluminationFilter> filter;
  filter->SetInputData(MakeFloor(1.0, 8)); // faces +z, the light is below
  filter->AddLight(MakeLight(light, at, 1.0));
  filter->SetBackendToCPU();
  filter->Update();
  EXPECT_TRUE(MessageCapture::Contains(Warnings(filter->GetOutput()), "Turn TwoSided on"));
  EXPECT_EQ(LitFraction(filter->GetOutput()), 0.0);

  filter->TwoSidedOn();
  filter->Update();
  EXPECT_FALSE(MessageCapture::Contains(Warnings(filter->GetOutput()), "Turn TwoSided on"));
  vtkDataArray* back = PointArray(filter->GetOutput(), "DirectIrradianceBack");
  ASSERT_NE(back, nullptr);
  EXPECT_GT(back->GetRange(0)[1], 0.0);
}

TEST(TestGlobalIlluminationRealData, NormalsSmoothedAcrossSharpEdgesAreSplit)
{
  // A box on a floor, its corners merged and their normals averaged over its faces (as CAD
  // exports write them): the box is lit as with ComputeNormals on, exactly, and the update
  // says so. vtkCubeSource's own normals (a normal per face) are kept, and say nothing.
  const double light[3] = { 2.0, 3.0, 4.0 }, at[3] = { 0, 0, 0 };
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-0.25, 0.25, -0.25, 0.25, 0.0, 0.5);
  vtkNew<vtkCleanPolyData> merged;
  merged->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkPolyDataNormals> averaged;
  averaged->SetInputConnection(merged->GetOutputPort());
  averaged->SplittingOff();
  averaged->Update();
  cube->Update();
  for (vtkPolyData* box : { averaged->GetOutput(), cube->GetOutput() })
  {
    const bool bent = box == averaged->GetOutput();
    vtkNew<vtkPolyDataNormals> floorNormals;
    floorNormals->SetInputData(MakeFloor(1.0, 1));
    floorNormals->Update();
    vtkNew<vtkAppendPolyData> scene;
    scene->AddInputData(box);
    scene->AddInputData(floorNormals->GetOutput());
    scene->Update();
    for (const int method : Methods)
    {
      vtkNew<vtkGlobalIlluminationFilter> filter;
      filter->SetInputData(scene->GetOutput());
      filter->AddLight(MakeLight(light, at, 1.0));
      filter->SetBackendToCPU();
      filter->SetMethod(method);
      filter->Update();
      const std::vector<std::string> warnings = Warnings(filter->GetOutput());
      EXPECT_EQ(MessageCapture::Contains(warnings, "averaged across sharp edges"), bent) << bent;
      EXPECT_EQ(MessageCapture::Contains(warnings, "lit with normals computed"), bent) << bent;
      vtkNew<vtkPolyData> given;
      given->DeepCopy(filter->GetOutput());
      filter->ComputeNormalsOn();
      filter->Update();
      EXPECT_TRUE(Warnings(filter->GetOutput()).empty()) << bent << ": " << Warnings(filter->GetOutput()).front();
      if (bent)
      {
        for (const char* name : Arrays)
        {
          EXPECT_EQ(Compare(given, filter->GetOutput(), name).Largest, 0.0) << method << ' ' << name;
        }
      }
    }
  }
}

TEST(TestGlobalIlluminationRealData, TranslationUpTo1e7ChangesNoResult)
{
  const double none[3] = { 0, 0, 0 };
  const double offsets[][3] = { { 1e3, -2e3, 5e2 }, { 4.5e5, 5.3e6, 120.0 }, { 1e7, 1e7, -1e7 } };
  for (const int method : Methods)
  {
    const vtkSmartPointer<vtkPolyData> reference = LitBunnyOnFloor(method, 1.0, none);
    for (const auto& offset : offsets)
    {
      std::vector<std::string> warnings;
      const vtkSmartPointer<vtkPolyData> moved = LitBunnyOnFloor(method, 1.0, offset, &warnings);
      EXPECT_FALSE(MessageCapture::Contains(warnings, "degenerate")) << method << " at " << offset[0];
      for (const char* name : Arrays)
      {
        // The input's own rounding at 1e7 (2e-9 m) moves some float positions by one ulp,
        // which can move one of implicit visibility's bin-centre rays across the edge of a
        // triangle it draws a near leaf from, so that the bin takes another source (1.3e-3),
        // and photon mapping's paths amplify: they leave the lamp towards the scene's
        // bounding sphere, whose extent moves by that ulp, so every path turns by about 1e-7
        // and those that graze an edge land elsewhere (1.1e-3 at the largest point).
        const Difference d = Compare(reference, moved, name);
        EXPECT_LT(d.Rms, 1e-4) << method << ' ' << name << " at " << offset[0];
        const bool paths = method == vtkGlobalIlluminationFilter::PHOTON_MAPPING;
        EXPECT_LT(d.Largest, DiscreteBins(method) || paths ? 3e-3 : 1e-3) << method << ' ' << name << " at " << offset[0];
      }
    }
  }
}

TEST(TestGlobalIlluminationRealData, MillimetresAndKilometresLightAsMetres)
{
  const double none[3] = { 0, 0, 0 };
  for (const int method : Methods)
  {
    const vtkSmartPointer<vtkPolyData> metres = LitBunnyOnFloor(method, 1.0, none);
    for (const double scale : { 1e3, 1e-3 })
    {
      const vtkSmartPointer<vtkPolyData> other = LitBunnyOnFloor(method, scale, none);
      for (const char* name : Arrays)
      {
        // Rounding at another scale moves single bins of implicit visibility to another
        // source, as above (RMS 1.9e-4, 6.8e-3 at the largest point).
        const Difference d = Compare(metres, other, name);
        EXPECT_LT(d.Rms, DiscreteBins(method) ? 3e-4 : 1e-4) << method << ' ' << name << " x" << scale;
        EXPECT_LT(d.Largest, DiscreteBins(method) ? 1.5e-2 : 2e-3) << method << ' ' << name << " x" << scale;
      }
    }
  }
}

TEST(TestGlobalIlluminationRealData, ARoomWithItsLampInsideKeepsItsNormals)
{
  // The unit cube wound inward, lit from inside (a room) and from outside (an object).
  const vtkSmartPointer<vtkPolyData> room = Reversed(MakeCube());
  const double inside[3] = { 0.5, 0.6, 0.4 }, outside[3] = { 2.5, 1.6, 3.0 }, at[3] = { 0.5, 0.5, 0.5 };
  for (const double* lamp : { inside, outside })
  {
    vtkNew<vtkGlobalIlluminationFilter> filter;
    filter->SetInputData(room);
    filter->AddLight(MakeLight(lamp, at, 1.0));
    filter->SetBackendToCPU();
    filter->Update();
    const bool turned = MessageCapture::Contains(Warnings(filter->GetOutput()), "lit from outside");
    EXPECT_EQ(turned, lamp == outside);
    EXPECT_GT(LitFraction(filter->GetOutput()), lamp == inside ? 0.99 : 0.3);
  }
}

TEST(TestGlobalIlluminationRealData, TheBudgetsProxyHoldsWhileOnlyTheLightsMove)
{
  if (!linkgi::proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  // The automatic budget (MemoryBudget 0) is what the machine has available less a margin
  // of 512 MiB: 512 MiB and 85% of the estimate of ~5.3k points at 256 rays available leave
  // too little for them (but more than their ray structures alone need).
  struct Available
  {
    explicit Available(std::uint64_t bytes) { linkgi::overrideAvailableHostBytes(bytes); }
    ~Available() { linkgi::overrideAvailableHostBytes(0); }
  };
  auto probe = MakeSphereOnFloorFilter(70);
  probe->SetRaysPerVertex(256);
  probe->Update();
  const auto estimate = std::uint64_t(Stat(probe->GetOutput(), "HostBytesEstimated"));
  ASSERT_GT(estimate, 0u);
  auto filter = MakeSphereOnFloorFilter(70);
  filter->SetRaysPerVertex(256);
  const auto proxyOf = [&filter]() {
    for (const std::string& w : Warnings(filter->GetOutput()))
    {
      const std::size_t at = w.find("proxy of about ");
      if (at != std::string::npos)
      {
        return std::stoul(w.substr(at + 15));
      }
    }
    return 0ul;
  };
  {
    Available tight((std::uint64_t(512) << 20) + estimate * 85 / 100);
    filter->Update();
  }
  const unsigned long first = proxyOf();
  ASSERT_GT(first, 0ul);
  EXPECT_FALSE(MessageCapture::Contains(Warnings(filter->GetOutput()), "previous result is kept"));

  // More memory frees up, and a light moves: the same proxy.
  Available roomier((std::uint64_t(512) << 20) + estimate * 95 / 100);
  const double moved[3] = { 0.7, 0.1, 2.2 }, at[3] = { 0, 0, 0 };
  filter->RemoveAllLights();
  filter->AddLight(MakeLight(moved, at, 4.0));
  filter->Update();
  EXPECT_EQ(proxyOf(), first);

  // A new surface is judged again, with what is available now.
  filter->SetFeatureAngle(filter->GetFeatureAngle() + 1.0);
  filter->Modified();
  filter->Update();
  EXPECT_GT(proxyOf(), first);
}

TEST(TestGlobalIlluminationRealData, AsynchronousUpdatesLogEachWarningOnce)
{
  // What ParaView's representation shows in its output messages: the asynchronous filter's
  // warnings (its own and the engine's), each once while it holds, not at every frame.
  const double below[3] = { 0.2, 0.1, -1.0 }, at[3] = { 0, 0, 0 };
  vtkNew<vtkGlobalIlluminationFilter> filter;
  filter->SetInputData(MakeFloor(1.0, 8));
  filter->AddLight(MakeLight(below, at, 1.0));
  filter->SetBackendToCPU();
  filter->SetAsynchronous(true);
  MessageCapture messages(filter);
  filter->Update();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
  while (!filter->PollAsynchronousResult() && std::chrono::steady_clock::now() < deadline)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  for (int frame = 0; frame < 5; ++frame)
  {
    filter->Modified();
    filter->Update();
  }
  int logged = 0;
  for (const std::string& w : messages.Warnings)
  {
    logged += w.find("Turn TwoSided on") != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(logged, 1);
}

TEST(TestGlobalIlluminationRealData, APointCloudIsAnErrorThatSaysHowToMakeASurface)
{
  // The bunny's points alone, as a scanner gives them (no cells, or one vertex cell each).
  for (const bool withVertexCells : { false, true })
  {
    auto cloud = vtkSmartPointer<vtkPolyData>::New();
    cloud->SetPoints(InwardBunny()->GetPoints());
    if (withVertexCells)
    {
      vtkNew<vtkCellArray> verts;
      for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
      {
        verts->InsertNextCell(1, &i);
      }
      cloud->SetVerts(verts);
    }
    vtkNew<vtkGlobalIlluminationFilter> filter;
    filter->SetInputData(cloud);
    filter->SetBackendToCPU();
    MessageCapture messages(filter);
    filter->Update();
    EXPECT_TRUE(messages.HasError("a point cloud has no surface to light")) << withVertexCells;
    EXPECT_TRUE(messages.HasError("vtkSurfaceReconstructionFilter")) << withVertexCells;
  }
}
