// Back faces take the indirect light of the filter's TwoSided output.
//
// A square with a reddish IndirectIrradiance and a bluish IndirectIrradianceBack, drawn in
// INDIRECT mode, looks red from the front and blue from behind. Without the Back array
// both sides show the front's values.
#include "RenderingTestUtilities.h"

namespace
{
using namespace linkgi_test;

vtkSmartPointer<vtkFloatArray> Constant(const char* name, vtkIdType n, double r, double g, double b)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    array->SetTuple3(i, r, g, b);
  }
  return array;
}

/// The colour in the middle of the window, looking at the square from +z or from -z.
std::array<double, 3> Seen(vtkRenderWindow* window, vtkPolyData* square, bool fromFront)
{
  vtkNew<vtkRenderer> renderer;
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, square);
  mapper->GetShading()->SetDisplayModeToIndirect();
  mapper->GetShading()->SetToneMappingToLinear();
  mapper->GetShading()->SetGamma(1.0);
  renderer->GetActiveCamera()->SetPosition(0, 0, fromFront ? 3 : -3);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  renderer->ResetCameraClippingRange();
  vtkSmartPointer<vtkImageData> image = RenderAlone(window, renderer);
  return { { Pixel(image, 50, 50, 0), Pixel(image, 50, 50, 1), Pixel(image, 50, 50, 2) } };
}
}

int TestGlobalIlluminationMapperTwoSided(int, char*[])
{
  vtkNew<vtkPlaneSource> plane; // normal +z: the front faces +z
  plane->Update();
  vtkNew<vtkPolyData> square;
  square->DeepCopy(plane->GetOutput());
  const vtkIdType n = square->GetNumberOfPoints();
  const double pi = vtkMath::Pi();
  // albedo / pi * E = 0.8 / pi * pi (0.9, 0.2, 0.1) = (0.72, 0.16, 0.08)
  square->GetPointData()->AddArray(Constant("Albedo", n, 0.8, 0.8, 0.8));
  square->GetPointData()->AddArray(Constant("IndirectIrradiance", n, 0.9 * pi, 0.2 * pi, 0.1 * pi));
  auto window = MakeWindow(100, 100);

  bool ok = true;
  const std::array<double, 3> front = Seen(window, square, true);
  const std::array<double, 3> backOneSided = Seen(window, square, false);
  square->GetPointData()->AddArray(
    Constant("IndirectIrradianceBack", n, 0.1 * pi, 0.2 * pi, 0.9 * pi));
  const std::array<double, 3> back = Seen(window, square, false);
  const std::array<double, 3> frontTwoSided = Seen(window, square, true);
  std::printf("front (%.0f %.0f %.0f), back without a Back array (%.0f %.0f %.0f), back (%.0f %.0f "
              "%.0f), front with it (%.0f %.0f %.0f)\n",
    front[0], front[1], front[2], backOneSided[0], backOneSided[1], backOneSided[2], back[0],
    back[1], back[2], frontTwoSided[0], frontTwoSided[1], frontTwoSided[2]);
  const auto near = [](const std::array<double, 3>& c, double r, double g, double b)
  {
    return std::abs(c[0] - 255 * r) <= 2 && std::abs(c[1] - 255 * g) <= 2 &&
      std::abs(c[2] - 255 * b) <= 2;
  };
  ok = Check(near(front, 0.72, 0.16, 0.08), "front: not the front's indirect light") && ok;
  ok =
    Check(near(backOneSided, 0.72, 0.16, 0.08), "back without a Back array: not the front's") && ok;
  ok = Check(near(back, 0.08, 0.16, 0.72), "back: not the Back array's indirect light") && ok;
  ok = Check(near(frontTwoSided, 0.72, 0.16, 0.08), "front with a Back array: changed") && ok;
  return ok ? 0 : 1;
}
