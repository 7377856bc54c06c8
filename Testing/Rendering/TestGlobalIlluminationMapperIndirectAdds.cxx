// Global illumination only adds light: in the closed Cornell box, the COMBINED image is at
// least as bright (luminance) as the DIRECT image at every pixel, and equal where no light
// arrives indirectly. To have such places in a closed box, the back wall's indirect light
// is zeroed; there the two images must agree to the level. Checked with the default
// (hue-preserving) display and with the photographic curve.
#include "RenderingTestUtilities.h"

#include "vtkGlobalIlluminationColors.h"

#include <cmath>

namespace
{
using namespace linkgi_test;

/// Relative luminance of an 8-bit sRGB pixel.
double Luminance(vtkImageData* image, int x, int y)
{
  const double w[3] = { 0.2126, 0.7152, 0.0722 };
  double sum = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    sum += w[k] * vtkGlobalIlluminationColors::ToLinear(Pixel(image, x, y, k) / 255.0);
  }
  return sum;
}

vtkSmartPointer<vtkImageData> Draw(vtkRenderWindow* window, vtkRenderer* lighting,
  vtkPolyData* box, int mode, int toneMapping, double exposure)
{
  vtkNew<vtkRenderer> renderer;
  AddLights(renderer, lighting->GetLights());
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, box);
  mapper->GetShading()->SetDisplayMode(mode);
  mapper->GetShading()->SetToneMapping(toneMapping);
  mapper->GetShading()->SetExposure(exposure);
  CornellCamera(renderer);
  return RenderAlone(window, renderer);
}

bool CheckAdds(vtkRenderWindow* window, vtkRenderer* lighting, vtkPolyData* box, int toneMapping,
  const std::string& name)
{
  vtkNew<vtkGlobalIlluminationShading> shading;
  shading->SetToneMapping(toneMapping);
  const double exposure = shading->SuggestExposure(box->GetPointData()->GetArray("Radiance"));
  using Shading = vtkGlobalIlluminationShading;
  auto direct = Draw(window, lighting, box, Shading::DIRECT, toneMapping, exposure);
  auto indirect = Draw(window, lighting, box, Shading::INDIRECT, toneMapping, exposure);
  auto combined = Draw(window, lighting, box, Shading::COMBINED, toneMapping, exposure);
  int darker = 0, unequal = 0, zero = 0, brighter = 0;
  double worst = 0.0;
  const int* size = window->GetSize();
  for (int y = 0; y < size[1]; ++y)
  {
    for (int x = 0; x < size[0]; ++x)
    {
      // One 8-bit level of slack for rounding.
      const double d = Luminance(direct, x, y), c = Luminance(combined, x, y);
      const double slack = vtkGlobalIlluminationColors::ToLinear(1.0 / 255.0);
      darker += c < d - slack ? 1 : 0;
      worst = std::max(worst, d - c);
      brighter += c > d + slack ? 1 : 0;
      // Lit surface (not the background) that no indirect light reaches.
      const bool noIndirect = d > 0.0 &&
        Pixel(indirect, x, y, 0) + Pixel(indirect, x, y, 1) + Pixel(indirect, x, y, 2) == 0.0;
      if (noIndirect)
      {
        ++zero;
        for (int k = 0; k < 3; ++k)
        {
          unequal += std::abs(Pixel(combined, x, y, k) - Pixel(direct, x, y, k)) > 1.0 ? 1 : 0;
        }
      }
    }
  }
  std::printf("%s: %d pixels darker in COMBINED than in DIRECT (largest luminance drop %.4f), "
              "%d brighter; %d pixels without indirect light, %d channels differ there\n",
    name.c_str(), darker, worst, brighter, zero, unequal);
  bool ok = Check(darker == 0, name + ": indirect light made pixels darker");
  ok = Check(brighter > 10000, name + ": the indirect light brightens the box") && ok;
  ok = Check(zero > 10000 && unequal == 0,
         name + ": without indirect light COMBINED must be DIRECT") && ok;
  return ok;
}
}

int TestGlobalIlluminationMapperIndirectAdds(int, char*[])
{
  vtkNew<vtkRenderer> lighting;
  vtkSmartPointer<vtkPolyData> lit = CornellBox(lighting);
  vtkNew<vtkPolyData> box;
  box->DeepCopy(lit);
  // No indirect light on the back wall (z = 0.559) and what shares its vertices.
  vtkDataArray* indirect = box->GetPointData()->GetArray("IndirectIrradiance");
  for (vtkIdType i = 0; i < box->GetNumberOfPoints(); ++i)
  {
    if (box->GetPoint(i)[2] > 0.55)
    {
      indirect->SetTuple3(i, 0.0, 0.0, 0.0);
    }
  }
  auto window = MakeWindow(300, 300);
  bool ok = CheckAdds(window, lighting, box, vtkGlobalIlluminationShading::HUE_PRESERVING,
    "hue preserving");
  ok = CheckAdds(window, lighting, box, vtkGlobalIlluminationShading::EXPONENTIAL, "exponential") &&
    ok;
  return ok ? 0 : 1;
}
