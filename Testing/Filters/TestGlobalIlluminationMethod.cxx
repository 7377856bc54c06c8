// vtkGlobalIlluminationFilter's Method: the switch between the link structure and instant
// radiosity, what each reports in the field data, and that both light the same scene alike.
#include "FilterTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include "linkgi/SolverTypes.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
std::string Method(vtkPolyData* pd)
{
  auto* names = vtkStringArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray("LinkGI.Method"));
  return names && names->GetNumberOfValues() > 0 ? names->GetValue(0) : "";
}

// Area-free mean of component 0 of a point array.
double Mean(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = PointArray(pd, name);
  double sum = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    sum += a->GetComponent(i, 0);
  }
  return sum / double(a->GetNumberOfTuples());
}

// Sphere (radius 0.4) above a 4 x 4 floor, lit by a point light.
vtkSmartPointer<vtkGlobalIlluminationFilter> SphereOnFloorFilter()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetRadius(0.4);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(MakeFloor(2, 20));
  append->AddInputConnection(sphere->GetOutputPort());
  append->Update();
  auto filter = vtkSmartPointer<vtkGlobalIlluminationFilter>::New();
  filter->SetInputData(append->GetOutput());
  const double light[3] = { 0.5, 0.3, 2.0 }, origin[3] = { 0, 0, 0 };
  filter->AddLight(MakeLight(light, origin, 4.0));
  filter->SetBackendToCPU();
  return filter;
}
}

TEST(TestGlobalIlluminationMethod, DefaultIsLinks)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  EXPECT_EQ(filter->GetMethod(), vtkGlobalIlluminationFilter::LINKS);
  EXPECT_STREQ(filter->GetMethodAsString(), "links");
  filter->SetMethodToInstantRadiosity();
  EXPECT_STREQ(filter->GetMethodAsString(), "instant-radiosity");
  {
    MessageCapture capture(filter);
    filter->SetMethod(77); // no such method: an error that names the ones there are
    EXPECT_TRUE(capture.HasError("No method 77; this build has 0 (links), 1 (instant-radiosity)"));
  }
  EXPECT_STREQ(filter->GetMethodAsString(), "instant-radiosity") << "unchanged";
  for (const linkgi::Method m : linkgi::methods())
  {
    filter->SetMethod(int(m));
    EXPECT_STREQ(filter->GetMethodAsString(), linkgi::methodName(m)) << "every registered method";
  }
  EXPECT_EQ(filter->GetNumberOfVPLs(), 1024);
  EXPECT_DOUBLE_EQ(filter->GetVPLClampDistance(), 0.02);
}

TEST(TestGlobalIlluminationMethod, SwitchingMethodsGivesTheSameArraysAndSimilarLight)
{
  auto filter = SphereOnFloorFilter();
  filter->Update();
  vtkNew<vtkPolyData> links;
  links->DeepCopy(filter->GetOutput());
  EXPECT_EQ(Method(links), "links");
  EXPECT_FALSE(std::isnan(Stat(links, "MsLinks")));
  EXPECT_TRUE(std::isnan(Stat(links, "Vpls"))) << "the link method reports no virtual point lights";
  EXPECT_GT(Stat(links, "LinksCompressed"), 0.0);

  filter->SetMethodToInstantRadiosity();
  filter->SetNumberOfVPLs(2048);
  filter->Update();
  vtkPolyData* ir = filter->GetOutput();
  EXPECT_EQ(Method(ir), "instant-radiosity");
  EXPECT_EQ(Stat(ir, "VplBuilds"), 1.0);
  // About NumberOfVPLs: paths that escape the open scene are made up by a second pass.
  EXPECT_NEAR(Stat(ir, "Vpls") / 2048.0, 1.0, 0.25);
  EXPECT_FALSE(std::isnan(Stat(ir, "MsGather")));
  EXPECT_TRUE(std::isnan(Stat(ir, "MsLinks"))) << "the link method's stages are gone";
  EXPECT_TRUE(std::isnan(Stat(ir, "LinksCompressed"))) << "and its counters";
  for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
  {
    ASSERT_NE(PointArray(ir, name), nullptr) << name;
    EXPECT_EQ(PointArray(ir, name)->GetNumberOfTuples(), PointArray(links, name)->GetNumberOfTuples());
  }
  // The same direct light (the shared stage); indirect light within 10% on average.
  EXPECT_NEAR(Mean(ir, "DirectIrradiance"), Mean(links, "DirectIrradiance"), 1e-6 * Mean(links, "DirectIrradiance"));
  EXPECT_NEAR(Mean(ir, "IndirectIrradiance") / Mean(links, "IndirectIrradiance"), 1.0, 0.10);

  // A VPL option re-traces the VPLs and gathers again, and leaves the direct light alone.
  filter->SetVPLInterleaving(4);
  filter->Update();
  EXPECT_EQ(Stat(filter->GetOutput(), "VplBuilds"), 2.0);
  EXPECT_EQ(Stat(filter->GetOutput(), "LightLinkBuilds"), 1.0);

  filter->SetMethodToLinks();
  filter->Update();
  EXPECT_EQ(Method(filter->GetOutput()), "links");
}

TEST(TestGlobalIlluminationMethod, EveryMethodBouncesALightAsItFallsOff)
{
  // A point light with VTK's default attenuation (no falloff) and one with a linear term: the
  // methods that shoot light from the lights carry what each lights, as the link method
  // bounces the direct light.
  for (const std::array<double, 3>& attenuation :
    { std::array<double, 3>{ { 1, 0, 0 } }, std::array<double, 3>{ { 0.5, 1, 0 } } })
  {
    auto filter = SphereOnFloorFilter();
    filter->GetLight(0)->SetAttenuationValues(attenuation.data());
    filter->Update();
    vtkNew<vtkPolyData> links;
    links->DeepCopy(filter->GetOutput());
    filter->SetMethodToInstantRadiosity();
    filter->SetNumberOfVPLs(2048);
    filter->Update();
    EXPECT_NEAR(Mean(filter->GetOutput(), "IndirectIrradiance") / Mean(links, "IndirectIrradiance"),
      1.0, 0.10)
      << "instant radiosity, attenuation " << attenuation[0] << ", " << attenuation[1];
    filter->SetMethodToPhotonMapping();
    filter->SetNumberOfPhotons(65536);
    filter->SetNumberOfClusters(512);
    filter->Update();
    EXPECT_NEAR(Mean(filter->GetOutput(), "IndirectIrradiance") / Mean(links, "IndirectIrradiance"),
      1.0, 0.10)
      << "photon mapping, attenuation " << attenuation[0] << ", " << attenuation[1];
  }
}

TEST(TestGlobalIlluminationMethod, ReferenceIsGroundTruthForTheOthers)
{
  // The reference path tracer as a method: the same arrays, its paths counted, and the link
  // method's indirect light within 10% of it on average; its direct light is exact (one
  // shadow ray per vertex, no light oversampling), so equal to the links' without it.
  auto filter = SphereOnFloorFilter();
  filter->SetLightOversampling(false);
  filter->Update();
  vtkNew<vtkPolyData> links;
  links->DeepCopy(filter->GetOutput());
  filter->SetMethodToReference();
  filter->SetReferencePathsPerVertex(256);
  filter->Update();
  vtkPolyData* reference = filter->GetOutput();
  EXPECT_EQ(Method(reference), "reference");
  EXPECT_EQ(Stat(reference, "Paths"), 256.0 * PointArray(reference, "IndirectIrradiance")->GetNumberOfTuples());
  EXPECT_EQ(Stat(reference, "PathRuns"), 1.0);
  EXPECT_NEAR(Mean(reference, "DirectIrradiance") / Mean(links, "DirectIrradiance"), 1.0, 1e-4);
  EXPECT_NEAR(Mean(links, "IndirectIrradiance") / Mean(reference, "IndirectIrradiance"), 1.0, 0.10);
}

TEST(TestGlobalIlluminationMethod, PhotonMappingLightsLikeTheLinksAndKeepsItsClustersOnALightMove)
{
  auto filter = SphereOnFloorFilter();
  filter->Update();
  vtkNew<vtkPolyData> links;
  links->DeepCopy(filter->GetOutput());

  filter->SetMethodToPhotonMapping();
  EXPECT_STREQ(filter->GetMethodAsString(), "photon-mapping");
  filter->SetNumberOfPhotons(65536);
  filter->SetNumberOfClusters(512);
  filter->Update();
  vtkPolyData* pm = filter->GetOutput();
  EXPECT_EQ(Method(pm), "photon-mapping");
  EXPECT_EQ(Stat(pm, "PhotonTraces"), 1.0);
  EXPECT_GT(Stat(pm, "Photons"), 10000.0);
  EXPECT_GT(Stat(pm, "Clusters"), 100.0);
  EXPECT_LE(Stat(pm, "Clusters"), 512.0);
  EXPECT_NEAR(Mean(pm, "DirectIrradiance"), Mean(links, "DirectIrradiance"), 1e-6 * Mean(links, "DirectIrradiance"));
  EXPECT_NEAR(Mean(pm, "IndirectIrradiance") / Mean(links, "IndirectIrradiance"), 1.0, 0.10);

  // A light move: new photons and gather, the same clusters.
  filter->GetLight(0)->SetPosition(-0.5, 0.3, 2.0);
  filter->Update();
  EXPECT_EQ(Stat(filter->GetOutput(), "PhotonTraces"), 2.0);
  EXPECT_EQ(Stat(filter->GetOutput(), "ClusterBuilds"), 1.0);

  filter->SetFinalGatherRays(200); // not a perfect square: an error that names it, output kept
  filter->Update();
  EXPECT_EQ(Method(filter->GetOutput()), "photon-mapping");
}


TEST(TestGlobalIlluminationMethod, GlassFocusesCausticsWithPhotonMapping)
{
  // The sphere on the floor as glass (a cell array: 2 on the sphere's cells, 0 on the
  // floor's): photon mapping adds CausticIrradiance on the floor; a bad value is an error
  // that names it and keeps the output; the link method lights the glass as diffuse and says so.
  auto filter = SphereOnFloorFilter();
  vtkPolyData* input = vtkPolyData::SafeDownCast(filter->GetInputDataObject(0, 0));
  vtkNew<vtkIntArray> material;
  material->SetName("Material");
  const vtkIdType floorCells = MakeFloor(2, 20)->GetNumberOfCells();
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    material->InsertNextValue(c < floorCells ? 0 : 2);
  }
  input->GetCellData()->AddArray(material);
  filter->SetMaterialArrayName("Material");
  filter->SetMethodToPhotonMapping();
  filter->SetNumberOfPhotons(65536);
  filter->SetNumberOfClusters(512);
  filter->Update();
  vtkDataArray* caustics = PointArray(filter->GetOutput(), "CausticIrradiance");
  ASSERT_NE(caustics, nullptr);
  double brightest = 0.0;
  for (vtkIdType i = 0; i < caustics->GetNumberOfTuples(); ++i)
  {
    brightest = std::max(brightest, caustics->GetComponent(i, 0));
  }
  EXPECT_GT(brightest, 0.0) << "the glass ball focuses light onto the floor";

  material->SetValue(0, 3);
  material->Modified();
  input->Modified();
  filter->Update();
  EXPECT_NE(PointArray(filter->GetOutput(), "CausticIrradiance"), nullptr) << "the previous output is kept";

  material->SetValue(0, 0);
  material->Modified();
  input->Modified();
  filter->SetMethodToLinks();
  filter->Update();
  auto* warnings = vtkStringArray::SafeDownCast(filter->GetOutput()->GetFieldData()->GetAbstractArray("LinkGI.Warnings"));
  bool said = false;
  for (vtkIdType i = 0; warnings && i < warnings->GetNumberOfValues(); ++i)
  {
    said = said || warnings->GetValue(i).find("as diffuse") != std::string::npos;
  }
  EXPECT_TRUE(said);
  EXPECT_EQ(PointArray(filter->GetOutput(), "CausticIrradiance"), nullptr);
}
