// vtkGlobalIlluminationFilter with Method IMPLICIT_VISIBILITY: the switch, its bins property,
// what it reports in the field data, and that it lights a scene like the link method.
#include "FilterTestUtilities.h"

#include "vtkGlobalIlluminationFilter.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

TEST(TestGlobalIlluminationImplicitVisibility, PropertiesAndTheirLimits)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 12);
  filter->SetMethodToImplicitVisibility();
  EXPECT_EQ(filter->GetMethod(), vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY);
  EXPECT_STREQ(filter->GetMethodAsString(), "implicit-visibility");
  filter->SetImplicitVisibilityBins(1);
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 2);
  filter->SetImplicitVisibilityBins(100);
  EXPECT_EQ(filter->GetImplicitVisibilityBins(), 32);
}

TEST(TestGlobalIlluminationImplicitVisibility, SwitchFromLinksGivesTheSameArraysAndSimilarLight)
{
  auto filter = MakeSphereOnFloorFilter();
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
  EXPECT_NEAR(MeanValue(iv, "DirectIrradiance"), MeanValue(links, "DirectIrradiance"), 1e-6 * MeanValue(links, "DirectIrradiance"));
  EXPECT_NEAR(MeanValue(iv, "IndirectIrradiance") / MeanValue(links, "IndirectIrradiance"), 1.0, 0.15);

  // More bins re-link and gather again, and leave the direct light alone.
  filter->SetImplicitVisibilityBins(8);
  filter->Update();
  EXPECT_EQ(Stat(filter->GetOutput(), "ImplicitLinkBuilds"), 2.0);
  EXPECT_EQ(Stat(filter->GetOutput(), "LightLinkBuilds"), 1.0);
}
