// Lights a sphere resting on a plane with one point light and writes the result, with its
// DirectIrradiance, IndirectIrradiance and Radiance point arrays, to a .vtp file.
// Usage: GlobalIlluminationSphereOnPlane out.vtp
#include "vtkAppendPolyData.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkSphereSource.h"
#include "vtkXMLPolyDataWriter.h"

#include <iostream>

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "Usage: " << argv[0] << " out.vtp\n";
    return 1;
  }
  vtkNew<vtkSphereSource> sphere; // radius 0.5, resting on the plane z = 0
  sphere->SetCenter(0, 0, 0.5);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPlaneSource> plane; // 4 x 4, facing +z
  plane->SetOrigin(-2, -2, 0);
  plane->SetPoint1(2, -2, 0);
  plane->SetPoint2(-2, 2, 0);
  plane->SetResolution(60, 60);
  vtkNew<vtkAppendPolyData> scene;
  scene->AddInputConnection(sphere->GetOutputPort());
  scene->AddInputConnection(plane->GetOutputPort());

  vtkNew<vtkLight> light; // 16 W/sr, 4 m up: irradiance 1 on the plane below it
  light->SetPositional(true);
  light->SetConeAngle(90);             // a point light, not a spot
  light->SetAttenuationValues(0, 0, 1); // a lamp: 1/r^2 (VTK's default does not fall off)
  light->SetPosition(0.5, 0.5, 4);
  light->SetIntensity(16);

  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputConnection(scene->GetOutputPort());
  gi->AddLight(light);
  gi->SetEnvironmentColor(0.05, 0.05, 0.08); // a dim sky
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(gi->GetOutputPort());
  writer->SetFileName(argv[1]);
  return writer->Write() == 1 ? 0 : 1;
}
