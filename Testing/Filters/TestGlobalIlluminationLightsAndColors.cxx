// vtkGlobalIlluminationLights and vtkGlobalIlluminationColors: the one reading of vtkLight
// and of colour arrays that the filter and the mapper's shadow maps share (the mapper's
// light type is the same struct; TestGlobalIlluminationMapperLightReading checks what it
// draws).
#include "FilterTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkGlobalIlluminationColors.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationLights.h"
#include "vtkMatrix4x4.h"
#include "vtkPlaneSource.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <limits>

using namespace linkgi_test;
using Lights = vtkGlobalIlluminationLights;
using Colors = vtkGlobalIlluminationColors;

namespace
{
const double Lamp[3] = { 1, 2, 3 }, Below[3] = { 1, 0, 3 };

Lights::Light Converted(vtkLight* light, double scale = 1.0)
{
  Lights::Light out;
  EXPECT_EQ(Lights::Convert(light, scale, out), Lights::CONVERTED);
  return out;
}

void ExpectNear(const std::array<double, 3>& a, double x, double y, double z, double tolerance = 1e-12)
{
  EXPECT_NEAR(a[0], x, tolerance);
  EXPECT_NEAR(a[1], y, tolerance);
  EXPECT_NEAR(a[2], z, tolerance);
}
}

TEST(GlobalIlluminationLights, ConeAnglesBelowNinetyAreSpotsTheRestPoints)
{
  for (double cone : { 89.0, 90.0, 180.0, 30.0 })
  {
    auto light = MakeLight(Lamp, Below, 1.0, true, cone);
    light->SetExponent(2.0);
    const Lights::Light l = Converted(light);
    EXPECT_EQ(l.Type, cone < 90.0 ? Lights::Light::SPOT : Lights::Light::POINT) << cone;
    EXPECT_EQ(l.ConeAngle, cone);
    EXPECT_NEAR(l.CosCone(), std::cos(cone * 3.14159265358979 / 180.0), 1e-12);
    EXPECT_EQ(l.Exponent, 2.0);
    ExpectNear(l.Position, 1, 2, 3);
    ExpectNear(l.Direction, 0, -1, 0); // unit, from the position to the focal point
  }
}

TEST(GlobalIlluminationLights, NonPositionalLightsAreDirectional)
{
  const double from[3] = { 0, 0, 4 }, to[3] = { 0, 3, 0 };
  auto sun = MakeLight(from, to, 1.0, false, 30.0); // the cone angle does not matter
  const Lights::Light l = Converted(sun);
  EXPECT_EQ(l.Type, Lights::Light::DIRECTIONAL);
  ExpectNear(l.Direction, 0, 0.6, -0.8);
}

TEST(GlobalIlluminationLights, IntensityIsColourTimesIntensityTimesScale)
{
  auto light = MakeLight(Lamp, Below, 2.0);
  light->SetDiffuseColor(1.0, 0.5, 0.25);
  light->SetAmbientColor(9, 9, 9); // only the diffuse colour counts
  light->SetSpecularColor(9, 9, 9);
  ExpectNear(Converted(light, 3.0).Intensity, 6.0, 3.0, 1.5);
  ExpectNear(Converted(light, 0.0).Intensity, 0.0, 0.0, 0.0);
  light->SetAttenuationValues(1, 5, 7); // the falloff, not the intensity
  ExpectNear(Converted(light, 1.0).Intensity, 2.0, 1.0, 0.5);
}

TEST(GlobalIlluminationLights, AttenuationIsReadAsVtkDefinesIt)
{
  auto bulb = vtkSmartPointer<vtkLight>::New(); // VTK's default: (1, 0, 0), no falloff
  bulb->SetPositional(true);
  bulb->SetPosition(Lamp[0], Lamp[1], Lamp[2]);
  bulb->SetConeAngle(180);
  Lights::Light l = Converted(bulb);
  ExpectNear(l.Attenuation, 1, 0, 0);
  EXPECT_FALSE(l.FallsOff());
  Lights::MakeLamp(bulb);
  l = Converted(bulb);
  ExpectNear(l.Attenuation, 0, 0, 1);
  EXPECT_TRUE(l.FallsOff());
  bulb->SetAttenuationValues(0.5, 0.25, 0);
  EXPECT_TRUE(Converted(bulb).FallsOff()); // a linear term falls off too
  Lights::Light forced;
  bulb->SetAttenuationValues(1, 0, 0);
  ASSERT_EQ(Lights::Convert(bulb, 1.0, forced, Lights::INVERSE_SQUARE), Lights::CONVERTED);
  ExpectNear(forced.Attenuation, 0, 0, 1); // the user's choice over the light's
  const double from[3] = { 0, 0, 4 }, to[3] = { 0, 0, 0 };
  auto sun = MakeLight(from, to, 1.0, false);
  EXPECT_FALSE(Converted(sun).FallsOff());
  ASSERT_EQ(Lights::Convert(sun, 1.0, forced, Lights::INVERSE_SQUARE), Lights::CONVERTED);
  EXPECT_FALSE(forced.FallsOff()); // a directional light never does
  Lights::Light out;
  for (const std::array<double, 3>& bad : { std::array<double, 3>{ { 0, 0, 0 } },
         std::array<double, 3>{ { 1, -1, 0 } } })
  {
    bulb->SetAttenuationValues(bad.data());
    EXPECT_EQ(Lights::Convert(bulb, 1.0, out), Lights::NOT_PHYSICAL);
    EXPECT_NE(Lights::Explain(Lights::NOT_PHYSICAL, bulb).find("attenuation"), std::string::npos);
  }
}

TEST(GlobalIlluminationLights, TheFilterFallsOffAsTheAttenuationSays)
{
  // A plane 40 units wide (the engine rescales it) under a point light 40 units above its
  // centre: the centre receives I / (c + l r + q r^2) for each attenuation.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-20, -20, 0);
  plane->SetPoint1(20, -20, 0);
  plane->SetPoint2(-20, 20, 0);
  plane->SetResolution(4, 4);
  plane->Update();
  const double above[3] = { 0, 0, 40 }, centre[3] = { 0, 0, 0 };
  for (const std::array<double, 3>& a : { std::array<double, 3>{ { 0, 0, 1 } },
         std::array<double, 3>{ { 1, 0, 0 } }, std::array<double, 3>{ { 0.5, 0.25, 0.001 } } })
  {
    auto light = MakeLight(above, centre, 2.0);
    light->SetAttenuationValues(a.data());
    vtkNew<vtkGlobalIlluminationFilter> gi;
    gi->SetInputData(plane->GetOutput());
    gi->AddLight(light);
    gi->SetRaysPerVertex(16);
    gi->SetNumberOfBounces(0);
    gi->SetBackend(vtkGlobalIlluminationFilter::CPU);
    gi->Update();
    vtkPolyData* out = gi->GetOutput();
    const vtkIdType middle = out->FindPoint(0, 0, 0);
    const double expected = 2.0 / (a[0] + a[1] * 40.0 + a[2] * 1600.0);
    EXPECT_NEAR(PointArray(out, "DirectIrradiance")->GetComponent(middle, 0), expected,
      1e-5 * expected)
      << a[0] << ", " << a[1] << ", " << a[2];
  }
}

TEST(GlobalIlluminationLights, SwitchedOffLightsAreSkippedSilently)
{
  auto light = MakeLight(Lamp, Below, 1.0);
  light->SwitchOff();
  Lights::Light out;
  out.Intensity = { { 7, 7, 7 } };
  EXPECT_EQ(Lights::Convert(light, 1.0, out), Lights::SWITCHED_OFF);
  EXPECT_EQ(Lights::Convert(nullptr, 1.0, out), Lights::SWITCHED_OFF);
  ExpectNear(out.Intensity, 7, 7, 7); // untouched
  EXPECT_TRUE(Lights::Explain(Lights::SWITCHED_OFF, light).empty());
}

TEST(GlobalIlluminationLights, SpotAndDirectionalLightsNeedADirectionPointLightsDoNot)
{
  Lights::Light out;
  auto spot = MakeLight(Lamp, Lamp, 1.0, true, 45.0);
  auto sun = MakeLight(Lamp, Lamp, 1.0, false);
  auto point = MakeLight(Lamp, Lamp, 1.0, true, 90.0);
  EXPECT_EQ(Lights::Convert(spot, 1.0, out), Lights::NO_DIRECTION);
  EXPECT_EQ(Lights::Convert(sun, 1.0, out), Lights::NO_DIRECTION);
  EXPECT_NE(Lights::Explain(Lights::NO_DIRECTION, spot).find("A spot light"), std::string::npos);
  EXPECT_NE(Lights::Explain(Lights::NO_DIRECTION, sun).find("A directional light"), std::string::npos);
  EXPECT_NE(Lights::Explain(Lights::NO_DIRECTION, sun).find("(1, 2, 3)"), std::string::npos);
  const Lights::Light l = Converted(point);
  EXPECT_EQ(l.Type, Lights::Light::POINT);
  ExpectNear(l.Direction, 0, 0, -1); // a unit placeholder, never NaN
}

TEST(GlobalIlluminationLights, NegativeOrNonFiniteLightsAreSkippedWithAWarning)
{
  Lights::Light out;
  out.Intensity = { { 7, 7, 7 } };
  auto negative = MakeLight(Lamp, Below, -1.0);
  EXPECT_EQ(Lights::Convert(negative, 1.0, out), Lights::NOT_PHYSICAL);
  EXPECT_EQ(Lights::Convert(MakeLight(Lamp, Below, 1.0), -2.0, out), Lights::NOT_PHYSICAL);
  auto reddish = MakeLight(Lamp, Below, 1.0);
  reddish->SetDiffuseColor(1.0, -0.5, 0.0);
  EXPECT_EQ(Lights::Convert(reddish, 1.0, out), Lights::NOT_PHYSICAL);
  const double nowhere[3] = { std::numeric_limits<double>::quiet_NaN(), 0, 0 };
  EXPECT_EQ(Lights::Convert(MakeLight(nowhere, Below, 1.0), 1.0, out), Lights::NOT_PHYSICAL);
  auto huge = MakeLight(Lamp, Below, std::numeric_limits<double>::infinity());
  EXPECT_EQ(Lights::Convert(huge, 1.0, out), Lights::NOT_PHYSICAL);
  ExpectNear(out.Intensity, 7, 7, 7); // untouched
  EXPECT_NE(Lights::Explain(Lights::NOT_PHYSICAL, negative).find("negative or non-finite"),
    std::string::npos);
  // A dark light is physical: it is read, and lights nothing.
  EXPECT_EQ(Lights::Convert(MakeLight(Lamp, Below, 0.0), 1.0, out), Lights::CONVERTED);

  // The filter warns and solves the rest of the scene instead of failing.
  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputData(MakeCube());
  gi->AddLight(negative);
  gi->AddLight(MakeLight(Lamp, Below, 1.0)); // a point light above the unit cube
  gi->SetRaysPerVertex(16);
  gi->SetBackend(vtkGlobalIlluminationFilter::CPU);
  MessageCapture messages(gi);
  gi->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.HasWarning("negative or non-finite"));
  EXPECT_GT(PointArray(gi->GetOutput(), "DirectIrradiance")->GetRange(0)[1], 0.0);
}

TEST(GlobalIlluminationLights, CameraLightsAreReadWhereTheRendererPlacedThem)
{
  auto light = MakeLight(Lamp, Below, 1.0);
  light->SetLightTypeToCameraLight();
  vtkNew<vtkMatrix4x4> shift; // what vtkRenderer sets from the camera
  shift->SetElement(0, 3, 10.0);
  light->SetTransformMatrix(shift);
  const Lights::Light l = Converted(light);
  ExpectNear(l.Position, 11, 2, 3);
  ExpectNear(l.Direction, 0, -1, 0);
}

TEST(GlobalIlluminationColors, UnsignedCharIsDecodedFromSRGBOtherTypesAreTakenAsTheyAre)
{
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetNumberOfComponents(4);
  const unsigned char rgba[4] = { 255, 188, 0, 7 };
  bytes->InsertNextTypedTuple(rgba);
  // sRGB 188 / 255 is 50 % linear light; alpha ignored.
  ExpectNear(Colors::Read(bytes, 0), 1.0, 0.5029, 0.0, 1e-4);

  vtkNew<vtkFloatArray> floats;
  floats->SetNumberOfComponents(3);
  floats->InsertNextTuple3(2.5, 0.5, 255.0); // HDR is kept
  ExpectNear(Colors::Read(floats, 0), 2.5, 0.5, 255.0);
}

TEST(GlobalIlluminationColors, OneAndTwoComponentsAreGrey)
{
  vtkNew<vtkDoubleArray> grey;
  grey->InsertNextValue(0.25);
  grey->InsertNextValue(3.0);
  ExpectNear(Colors::Read(grey, 0), 0.25, 0.25, 0.25);
  ExpectNear(Colors::Read(grey, 1), 3.0, 3.0, 3.0);

  vtkNew<vtkUnsignedCharArray> greyAlpha;
  greyAlpha->SetNumberOfComponents(2);
  greyAlpha->InsertNextTuple2(10, 255); // on the sRGB curve's linear segment
  ExpectNear(Colors::Read(greyAlpha, 0), 10 / 255. / 12.92, 10 / 255. / 12.92, 10 / 255. / 12.92);

  vtkNew<vtkFloatArray> five; // more than four: the first three
  five->SetNumberOfComponents(5);
  five->InsertNextTuple(std::array<double, 5>{ { 0.1, 0.2, 0.3, 0.4, 0.5 } }.data());
  ExpectNear(Colors::Read(five, 0), 0.1, 0.2, 0.3, 1e-7);
}

TEST(GlobalIlluminationColors, DisplayAndLinearAreInverseSRGBCurves)
{
  for (int i = 0; i <= 255; ++i)
  {
    EXPECT_NEAR(Colors::ToDisplay(Colors::ToLinear(i / 255.0)), i / 255.0, 1e-12);
  }
  EXPECT_NEAR(Colors::ToLinear(0.5), 0.21404, 1e-5);
  EXPECT_EQ(Colors::ToLinear(2.0), 1.0);
  EXPECT_EQ(Colors::ToDisplay(-1.0), 0.0);
  EXPECT_EQ(Colors::ToLinear(std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(GlobalIlluminationColors, ClampKeepsAlbedoInZeroOneAndRadiometryNonNegative)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Colors::RGB values = { { 1.5, nan, -0.25 } };
  ExpectNear(Colors::Clamp(values, Colors::REFLECTANCE), 1.0, 0.0, 0.0);
  ExpectNear(Colors::Clamp(values, Colors::RADIOMETRIC), 1.5, 0.0, 0.0);
  ExpectNear(Colors::Clamp({ { 0.5, 0.0, 1.0 } }, Colors::REFLECTANCE), 0.5, 0.0, 1.0);
  EXPECT_EQ(Colors::Clamp({ { inf, 0, 0 } }, Colors::REFLECTANCE)[0], 1.0);
  EXPECT_EQ(Colors::Clamp({ { inf, 0, 0 } }, Colors::RADIOMETRIC)[0], inf);

  vtkNew<vtkFloatArray> withNaN; // as the mapper reads an array: Read, then Clamp
  withNaN->SetNumberOfComponents(3);
  withNaN->InsertNextTuple3(nan, 2.0, 0.5);
  ExpectNear(Colors::Clamp(Colors::Read(withNaN, 0), Colors::REFLECTANCE), 0.0, 1.0, 0.5);
}

TEST(GlobalIlluminationColors, TheFilterSolvesWithWhatClampGivesTheMapper)
{
  // Albedo above 1 in a float array: the filter's ClampAlbedo repair is Clamp(REFLECTANCE).
  vtkSmartPointer<vtkPolyData> floor = MakeFloor(1, 2);
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < floor->GetNumberOfPoints(); ++i)
  {
    albedo->InsertNextTuple3(1.5, 0.5, 0.25);
  }
  floor->GetPointData()->AddArray(albedo);
  vtkNew<vtkGlobalIlluminationFilter> filter;
  filter->SetInputData(floor);
  filter->SetRaysPerVertex(16);
  filter->SetAlbedoArrayName("Albedo");
  const double above[3] = { 0, 0, 1 }, origin[3] = { 0, 0, 0 };
  filter->AddLight(MakeLight(above, origin, 1.0, false));
  MessageCapture messages(filter);
  filter->Update();
  EXPECT_TRUE(messages.HasWarning("Clamped the albedo"));
  // A lone floor under the sun: E = 1, L = albedo / pi.
  const Colors::RGB drawn = Colors::Clamp(Colors::Read(albedo, 0), Colors::REFLECTANCE);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(Value(filter->GetOutput(), "Radiance", 0, c) * 3.14159265358979, drawn[c], 1e-5);
  }
}
