// Data at geo-referenced coordinates draws as it does at the origin.
//
// The objects on the ground under a point light (cube shadow map), a spot light and a
// directional light, each alone, with the filter's indirect light, rendered once at the
// origin and once moved (data, camera and light) by an offset in double precision: 1e5
// (a UTM easting) and 1e7 (beyond any UTM coordinate). In single precision a position at
// 1e7 is rounded to 1 unit, so shadow maps built in world coordinates turn into blocks and
// stripes; in the mapper's frame (the world less the casters' centre) nothing may change:
// mean difference below 0.5 levels and at most 0.2% of the pixels 8 levels apart (pixels
// on the edges of shadows may round to the other side).
#include "RenderingTestUtilities.h"

#include <cstdio>

namespace
{
using namespace linkgi_test;

vtkSmartPointer<vtkPolyData> Moved(vtkPolyData* data, const double offset[3])
{
  vtkNew<vtkTransform> move;
  move->Translate(offset);
  vtkNew<vtkTransformPolyDataFilter> moved;
  moved->SetInputData(data);
  moved->SetTransform(move);
  moved->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  moved->Update();
  return moved->GetOutput();
}

vtkSmartPointer<vtkImageData> Render(vtkRenderWindow* window, int kind, const double offset[3])
{
  vtkNew<vtkRenderer> renderer;
  const double white[3] = { 1, 1, 1 };
  const double position[3] = { -1.2 + offset[0], -0.8 + offset[1], 1.6 + offset[2] };
  const double focal[3] = { offset[0], offset[1], offset[2] };
  const double cone[3] = { 90.0, 40.0, 0.0 }, intensity[3] = { 2.0, 3.0, 1.0 };
  renderer->AddLight(SceneLight(position, focal, cone[kind], intensity[kind], white));
  vtkGlobalIlluminationMapper* mapper =
    AddMappedActor(renderer, Illuminate(Moved(ObjectsOnGround(), offset), renderer, 16));
  mapper->GetShading()->SetExposure(1.0);
  GroundCamera(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  double p[3], f[3];
  camera->GetPosition(p);
  camera->GetFocalPoint(f);
  camera->SetPosition(p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]);
  camera->SetFocalPoint(f[0] + offset[0], f[1] + offset[1], f[2] + offset[2]);
  renderer->ResetCameraClippingRange();
  return RenderAlone(window, renderer);
}
}

int TestGlobalIlluminationMapperFarFromOrigin(int argc, char* argv[])
{
  vtkSmartPointer<vtkRenderWindow> window = MakeWindow(400, 300);
  const double none[3] = { 0, 0, 0 };
  const double offsets[2][3] = { { 4.5e5, 5.3e6, 120.0 }, { 1e7, -1e7, 1e7 } };
  const char* const kinds[3] = { "point", "spot", "directional" };
  bool ok = true;
  for (int kind = 0; kind < 3; ++kind)
  {
    const vtkSmartPointer<vtkImageData> atOrigin = Render(window, kind, none);
    int dims[3];
    atOrigin->GetDimensions(dims);
    const int pixels = dims[0] * dims[1];
    for (const auto& offset : offsets)
    {
      const ImageDifference d = Difference(atOrigin, Render(window, kind, offset), 8.0);
      std::printf("%s light at %g: mean difference %.3f levels, %d of %d pixels above 8\n",
        kinds[kind], offset[0], d.Mean, d.Above, pixels);
      ok = Check(d.Mean < 0.5 && d.Above <= pixels / 500,
             std::string("the ") + kinds[kind] + " light's picture changes when moved by " +
               std::to_string(offset[0])) &&
        ok;
    }
  }
  // The picture itself (point light at the origin) against its baseline.
  Render(window, 0, none);
  return CompareWithBaseline(argc, argv, window) == 0 && ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
