// The mapper reads lights and colours with the filter's functions (vtkGlobalIlluminationLights,
// vtkGlobalIlluminationColors): a spot light without a direction is skipped by both with the
// same warning (once, not per frame), and an albedo above 1 is drawn as 1, NaN as 0.
#include "RenderingTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkGlobalIlluminationLights.h"

#include <limits>

namespace
{
/// The warnings `object` sends while alive.
struct Warnings
{
  explicit Warnings(vtkObject* object)
    : Object(object)
  {
    this->Command->SetClientData(&this->Messages);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* list, void* text) {
      static_cast<std::vector<std::string>*>(list)->push_back(static_cast<const char*>(text));
    });
    this->Tag = object->AddObserver(vtkCommand::WarningEvent, this->Command);
  }
  ~Warnings() { this->Object->RemoveObserver(this->Tag); }
  int Count(const std::string& part) const
  {
    return static_cast<int>(std::count_if(this->Messages.begin(), this->Messages.end(),
      [&](const std::string& m) { return m.find(part) != std::string::npos; }));
  }
  std::vector<std::string> Messages;
  vtkNew<vtkCallbackCommand> Command;
  vtkObject* Object;
  unsigned long Tag = 0;
};

/// A unit floor facing +z with a constant float albedo `rho` (grey).
vtkSmartPointer<vtkPolyData> Floor(double rho)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(4, 4);
  return linkgi_test::WithAlbedo(plane, rho, rho, rho);
}

bool SameImages(vtkImageData* a, vtkImageData* b)
{
  int dims[3];
  a->GetDimensions(dims);
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (linkgi_test::Pixel(a, x, y, k) != linkgi_test::Pixel(b, x, y, k))
        {
          return false;
        }
      }
    }
  }
  return true;
}
}

int TestGlobalIlluminationMapperLightReading(int, char*[])
{
  using namespace linkgi_test;
  bool ok = true;
  const double above[3] = { 0, 0, 1 }, origin[3] = { 0, 0, 0 }, white[3] = { 1, 1, 1 };
  auto sun = SceneLight(above, origin, 0.0, 1.0, white);
  auto aimless = SceneLight(above, above, 30.0, 1.0, white); // a spot with focal == position
  const std::string expected =
    vtkGlobalIlluminationLights::Explain(vtkGlobalIlluminationLights::NO_DIRECTION, aimless);

  auto window = MakeWindow(80, 80);
  const auto render = [&](double rho) {
    vtkNew<vtkRenderer> renderer;
    renderer->AddLight(sun);
    renderer->AddLight(aimless);
    vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, Floor(rho));
    mapper->GetShading()->SetDisplayModeToDirect();
    Warnings warnings(mapper);
    renderer->ResetCamera();
    auto image = RenderAlone(window, renderer);
    window->Render(); // a second frame warns no more
    ok &= Check(warnings.Count(expected) == 1, "the mapper warned once with the filter's sentence");
    return image;
  };
  const auto one = render(1.0), above1 = render(1.5), zero = render(0.0);
  const auto nan = render(std::numeric_limits<double>::quiet_NaN());
  ok &= Check(Pixel(one, 40, 40, 0) > 20.0, "the sun lights the floor; the aimless spot did not stop it");
  ok &= Check(SameImages(one, above1), "albedo 1.5 is drawn as 1, as the filter clamps it");
  ok &= Check(SameImages(zero, nan), "NaN albedo is drawn as 0");

  // The filter, given the same lights, skips the same light with the same sentence.
  vtkNew<vtkRenderer> lights;
  lights->AddLight(sun);
  lights->AddLight(aimless);
  vtkNew<vtkGlobalIlluminationFilter> gi;
  gi->SetInputData(Floor(0.5));
  gi->SetRaysPerVertex(16);
  gi->SetLightsFromRenderer(lights);
  Warnings filterWarnings(gi);
  gi->Update();
  ok &= Check(filterWarnings.Count(expected) == 1, "the filter warned with the same sentence");
  ok &= Check(std::abs(gi->GetOutput()->GetPointData()->GetArray("DirectIrradiance")->GetTuple3(0)[0] - 1.0) < 1e-4,
    "the filter lit the floor with the sun alone");
  return ok ? 0 : 1;
}
