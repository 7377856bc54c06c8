// The optional glossy lobe: normalized Blinn-Phong, (m + 8) / (8 pi) (n.h)^m times the
// irradiance, scaled by the actor's Specular and SpecularColor, m = SpecularPower.
//
// A plane (colour 0.8: albedo 0.604 in linear light) under a point light at (-0.5, 0, 1), seen from (0.5, 0, 1): at the
// origin the half vector is the normal, so the pixel there is (0.604 / pi + ks (m + 8) /
// (8 pi)) E with E = 1 / 1.25^1.5, in linear output. Without Specular only the diffuse part.
#include "RenderingTestUtilities.h"
#include "vtkGlobalIlluminationColors.h"

namespace
{
using namespace linkgi_test;

double CentreValue(vtkRenderWindow* window, vtkPolyData* plane, vtkLight* light, double specular)
{
  vtkNew<vtkRenderer> renderer;
  renderer->AddLight(light);
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, plane);
  mapper->GetShading()->SetDisplayModeToDirect();
  mapper->GetShading()->SetToneMappingToLinear();
  mapper->GetShading()->SetGamma(1.0);
  vtkActor* actor = renderer->GetActors()->GetLastActor();
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  actor->GetProperty()->SetSpecular(specular);
  actor->GetProperty()->SetSpecularColor(1, 1, 1);
  actor->GetProperty()->SetSpecularPower(50);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
  vtkSmartPointer<vtkImageData> image = RenderAlone(window, renderer);
  return Pixel(image, 100, 100, 1);
}
}

int TestGlobalIlluminationMapperGlossy(int, char*[])
{
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(-2, -2, 0);
  source->SetPoint1(2, -2, 0);
  source->SetPoint2(-2, 2, 0);
  source->Update();
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetAttenuationValues(0, 0, 1); // a lamp: 1/r^2
  light->SetConeAngle(180);
  light->SetPosition(-0.5, 0, 1);
  auto window = MakeWindow(200, 200);

  const double e = 1.0 / std::pow(1.25, 1.5), pi = vtkMath::Pi();
  const double diffuse = vtkGlobalIlluminationColors::ToLinear(0.8) / pi * e, glossy = 0.3 * 58.0 / (8.0 * pi) * e;
  const double matte = CentreValue(window, source->GetOutput(), light, 0.0);
  const double shiny = CentreValue(window, source->GetOutput(), light, 0.3);
  std::printf("centre pixel: matte %.1f (expected %.1f), glossy %.1f (expected %.1f)\n", matte,
    255.0 * diffuse, shiny, 255.0 * (diffuse + glossy));
  bool ok = Check(std::abs(matte - 255.0 * diffuse) <= 2.0, "diffuse value");
  ok = Check(std::abs(shiny - 255.0 * (diffuse + glossy)) <= 3.0, "glossy value") && ok;
  return ok ? 0 : 1;
}
