// vtkGlobalIlluminationFilter's MemoryBudget and ProxyVertices: a budget too small
// for the update is an error that keeps the previous output; a proxy lights every input point,
// with the direct light of the full surface, and bad proxy sizes are errors.
#include "FilterTestUtilities.h"

#include "vtkGlobalIlluminationFilter.h"

#include "linkgi/Resolution.h"

#include <gtest/gtest.h>

using namespace linkgi_test;

namespace
{
// The shared sphere over a floor, at 64 rays (the proxy tests need no more).
vtkSmartPointer<vtkGlobalIlluminationFilter> SphereOnFloorFilter(int floorResolution = 30)
{
  auto filter = MakeSphereOnFloorFilter(floorResolution);
  filter->SetRaysPerVertex(64);
  return filter;
}

bool SameArray(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      if (a->GetComponent(i, c) != b->GetComponent(i, c))
      {
        return false;
      }
    }
  }
  return true;
}
}

TEST(TestGlobalIlluminationProxy, PropertiesAndTheirDefaults)
{
  vtkNew<vtkGlobalIlluminationFilter> filter;
  EXPECT_EQ(filter->GetMemoryBudget(), 0.0);
  EXPECT_EQ(filter->GetProxyVertices(), 0);
  filter->SetMemoryBudget(-5.0);
  EXPECT_EQ(filter->GetMemoryBudget(), 0.0);
}

TEST(TestGlobalIlluminationProxy, ABudgetTooSmallIsAnErrorAndKeepsTheOutput)
{
  auto filter = SphereOnFloorFilter();
  filter->Update();
  vtkNew<vtkPolyData> before;
  before->DeepCopy(filter->GetOutput());

  MessageCapture messages(filter);
  filter->SetMemoryBudget(0.5); // MiB: not enough for 1024 rays on ~1.2k points
  filter->SetRaysPerVertex(1024);
  filter->Update();
  EXPECT_TRUE(messages.HasError("Not enough memory")) << (messages.Errors.empty() ? "" : messages.Errors[0]);
  EXPECT_TRUE(messages.HasError("rays per vertex"));
  EXPECT_TRUE(SameArray(PointArray(filter->GetOutput(), "IndirectIrradiance"),
    PointArray(before, "IndirectIrradiance")));
}

TEST(TestGlobalIlluminationProxy, AProxyLightsEveryPointWithTheFullDirectLight)
{
  if (!linkgi::proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  auto filter = SphereOnFloorFilter();
  filter->Update();
  vtkNew<vtkPolyData> full;
  full->DeepCopy(filter->GetOutput());
  const vtkIdType points = full->GetNumberOfPoints();

  MessageCapture messages(filter);
  filter->SetProxyVertices(points / 3);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  EXPECT_TRUE(messages.Errors.empty()) << messages.Errors[0];
  ASSERT_EQ(out->GetNumberOfPoints(), points);
  EXPECT_TRUE(SameArray(PointArray(out, "DirectIrradiance"), PointArray(full, "DirectIrradiance")));
  vtkDataArray* indirect = PointArray(out, "IndirectIrradiance");
  ASSERT_NE(indirect, nullptr);
  EXPECT_FALSE(SameArray(indirect, PointArray(full, "IndirectIrradiance"))); // it did go through a proxy
  EXPECT_GT(indirect->GetRange(0)[1], 0.0);

  filter->SetProxyVertices(2 * points); // more than the input has, split normals included
  filter->Update();
  EXPECT_TRUE(messages.HasError("fewer vertices than the input"));
  messages.Clear();
  filter->SetProxyVertices(-1);
  filter->Update();
  EXPECT_TRUE(messages.HasError("ProxyVertices must be 0"));
}

TEST(TestGlobalIlluminationProxy, OverTheBudgetAProxyThatFitsLightsTheSurface)
{
  if (!linkgi::proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  // ~5.3k points at 256 rays: a budget of 85% of their estimate (more than their ray
  // structures alone need) fits a proxy of about half.
  auto probe = SphereOnFloorFilter(70);
  probe->SetRaysPerVertex(256);
  probe->Update();
  const double estimate = Stat(probe->GetOutput(), "HostBytesEstimated");
  ASSERT_GT(estimate, 0.0);
  auto filter = SphereOnFloorFilter(70);
  filter->SetRaysPerVertex(256);
  filter->SetMemoryBudget(0.85 * estimate / (1024.0 * 1024.0));
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty()) << messages.Errors[0];
  EXPECT_TRUE(messages.HasWarning("lit through a proxy of about"));
  EXPECT_LE(Stat(filter->GetOutput(), "HostBytesEstimated"), 0.85 * estimate);
  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* indirect = PointArray(out, "IndirectIrradiance");
  ASSERT_NE(indirect, nullptr);
  EXPECT_EQ(indirect->GetNumberOfTuples(), out->GetNumberOfPoints());
  EXPECT_GT(indirect->GetRange(0)[1], 0.0);
}

TEST(TestGlobalIlluminationProxy, ImplicitVisibilityOverTheBudgetGoesThroughAProxy)
{
  if (!linkgi::proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  // Its own estimate, then a budget of 75% of it: the same automatic proxy as the link
  // method's, whose estimate fits that budget. (Instant radiosity and photon mapping take
  // the same path on a closed scene; over this open floor most of their light paths leave,
  // and the second pass of paths is what a tight budget refuses: TestMemoryBudget.)
  auto probe = SphereOnFloorFilter(70);
  probe->SetMethod(vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY);
  probe->Update();
  const double estimate = Stat(probe->GetOutput(), "HostBytesEstimated");
  ASSERT_GT(estimate, 0.0);

  auto filter = SphereOnFloorFilter(70);
  filter->SetMethod(vtkGlobalIlluminationFilter::IMPLICIT_VISIBILITY);
  filter->SetMemoryBudget(0.75 * estimate / (1024.0 * 1024.0));
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty()) << messages.Errors[0];
  EXPECT_TRUE(messages.HasWarning("lit through a proxy of about"));
  EXPECT_TRUE(messages.HasWarning("implicit-visibility method"));
  EXPECT_LE(Stat(filter->GetOutput(), "HostBytesEstimated"), 0.75 * estimate);
  vtkDataArray* indirect = PointArray(filter->GetOutput(), "IndirectIrradiance");
  ASSERT_NE(indirect, nullptr);
  EXPECT_EQ(indirect->GetNumberOfTuples(), filter->GetOutput()->GetNumberOfPoints());
  EXPECT_GT(indirect->GetRange(0)[1], 0.0);
}
