// vtkGlobalIlluminationFilter with Method IMPLICIT_VISIBILITY: the switch, its bins property,
// what it reports in the field data, and that it lights a scene like the link method.
#include "FilterTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
std::string MethodName(vtkPolyData* pd)
{
  auto* names = vtkStringArray::SafeDownCast(pd->GetFieldData()->GetAbstractArray("LinkGI.Method"));
  return names && names->GetNumberOfValues() > 0 ? names->GetValue(0) : "";
}

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

// A sphere (radius 0.4) above a 4 x 4 floor, lit by a point light.
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

TEST(TestGlobalIlluminationImplicitVisibility, PropertiesAndTheirLimits)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 12);
  filter->SetMethodToImplicitVisibility();
  EXPECT_EQ(filter->GetMethod(), vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY);
  EXPECT_STREQ(filter->GetMethodAsString(), "ImplicitVisibility");
  filter->SetImplicitVisibilityBins(1);
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 2);
  filter->SetImplicitVisibilityBins(100);
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 32);
}

TEST(TestGlobalIlluminationImplicitVisibility, SwitchFromLinksGivesTheSameArraysAndSimilarLight)
{
  auto filter = SphereOnFloorFilter();
  filter->Update();
  vtkNew<vtkPolyData> links;
  links->DeepCopy(filter->GetOutput());
  EXPECT_EQ(MethodName(links), "links");

  filter->SetMethodToImplicitVisibility();
  filter->Update();
  vtkPolyData* iv = filter->GetOutput();
  EXPECT_EQ(MethodName(iv), "implicit-visibility");
  EXPECT_EQ(Stat(iv, "ImplicitLinkBuilds"), 1.0);
  EXPECT_FALSE(std::isnan(Stat(iv, "MsImplicitLinks")));
  EXPECT_TRUE(std::isnan(Stat(iv, "MsLinks"))) << "the link method's stages are gone";
  for (const char* name : { "DirectIrradiance", "IndirectIrradiance", "Radiance" })
  {
    ASSERT_NE(PointArray(iv, name), nullptr) << name;
    EXPECT_EQ(PointArray(iv, name)->GetNumberOfTuples(), PointArray(links, name)->GetNumberOfTuples());
  }
  // The same direct light (the shared light-link stage); bounced light within 15% on
  // average (the bins' full coverage brightens what the floor sees of the sphere).
  EXPECT_NEAR(Mean(iv, "DirectIrradiance"), Mean(links, "DirectIrradiance"), 1e-6 * Mean(links, "DirectIrradiance"));
  EXPECT_NEAR(Mean(iv, "IndirectIrradiance") / Mean(links, "IndirectIrradiance"), 1.0, 0.15);

  // More bins re-link and gather again, and leave the direct light alone.
  filter->SetImplicitVisibilityBins(8);
  filter->Update();
  EXPECT_EQ(Stat(filter->GetOutput(), "ImplicitLinkBuilds"), 2.0);
  EXPECT_EQ(Stat(filter->GetOutput(), "LightLinkBuilds"), 1.0);
}
