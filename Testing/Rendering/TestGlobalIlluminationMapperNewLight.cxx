// A new result of the filter changes only its light arrays, and vtkGlobalIlluminationMapper
// then uploads the shading attributes alone instead of rebuilding all its buffers
// (vtkGlobalIlluminationMapperCore::GeometryKey). Whatever path it takes, the picture after
// the change must be the one a new mapper draws of the same data:
// - a new, brighter IndirectIrradiance array on the Cornell box;
// - the same while the mapper colours the box by that array (without an albedo array, so
//   the colours are the albedo): the colours are in VTK's own buffers, so the mapper must
//   rebuild those, light array or not;
// - the same after a hardware point selection of the box.
#include "RenderingTestUtilities.h"

#include "vtkHardwareSelector.h"
#include "vtkPointData.h"
#include "vtkSelection.h"

#include <cmath>

namespace
{
using namespace linkgi_test;

double LargestDifference(vtkImageData* a, vtkImageData* b)
{
  double worst = 0.0;
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  for (vtkIdType p = 0; p < x->GetNumberOfTuples(); ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      worst = std::max(worst, std::abs(x->GetComponent(p, k) - y->GetComponent(p, k)));
    }
  }
  return worst;
}

struct Scene
{
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkGlobalIlluminationMapper* Mapper;
};

Scene MakeScene(vtkRenderer* lighting, vtkPolyData* data, double exposure, bool coloured)
{
  Scene scene{ vtkSmartPointer<vtkRenderer>::New(), nullptr };
  AddLights(scene.Renderer, lighting->GetLights());
  scene.Mapper = AddMappedActor(scene.Renderer, data);
  scene.Mapper->GetShading()->SetExposure(exposure);
  if (coloured)
  {
    scene.Mapper->ScalarVisibilityOn();
    scene.Mapper->SetScalarModeToUsePointFieldData();
    scene.Mapper->SelectColorArray("IndirectIrradiance");
    scene.Mapper->SetScalarRange(0.0, 2.0);
  }
  CornellCamera(scene.Renderer);
  return scene;
}
}

int TestGlobalIlluminationMapperNewLight(int, char*[])
{
  vtkNew<vtkRenderer> lighting;
  vtkSmartPointer<vtkPolyData> lit = CornellBox(lighting);
  const double exposure = AutoExposure(lit->GetPointData()->GetArray("Radiance"));
  vtkDataArray* indirect = lit->GetPointData()->GetArray("IndirectIrradiance");
  vtkNew<vtkFloatArray> brighter;
  brighter->DeepCopy(indirect);
  for (vtkIdType i = 0; i < brighter->GetNumberOfValues(); ++i)
  {
    brighter->SetValue(i, 3.0f * brighter->GetValue(i));
  }
  auto window = MakeWindow(200, 200);
  bool ok = true;
  for (const int variant : { 0, 1, 2 })
  {
    const bool coloured = variant == 1, selected = variant == 2;
    vtkNew<vtkPolyData> box;
    box->ShallowCopy(lit);
    if (coloured)
    {
      box->GetPointData()->RemoveArray("Albedo");
    }
    Scene scene = MakeScene(lighting, box, exposure, coloured);
    vtkSmartPointer<vtkImageData> before = RenderAlone(window, scene.Renderer);
    if (selected)
    {
      vtkNew<vtkHardwareSelector> selector;
      selector->SetRenderer(scene.Renderer);
      selector->SetArea(0, 0, 199, 199);
      selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);
      vtkSmartPointer<vtkSelection> picked = vtk::TakeSmartPointer(selector->Select());
      ok = Check(picked && picked->GetNumberOfNodes() > 0, "the point selection picked nothing") && ok;
    }
    box->GetPointData()->AddArray(brighter); // replaces IndirectIrradiance, as a new result does
    window->Render();                         // the same renderer: its buffers are kept
    vtkSmartPointer<vtkImageData> after = Capture(window);
    Scene fresh = MakeScene(lighting, box, exposure, coloured);
    vtkSmartPointer<vtkImageData> expected = RenderAlone(window, fresh.Renderer);
    const double changed = LargestDifference(before, after);
    const double unlike = LargestDifference(after, expected);
    const char* what = coloured ? "coloured by the indirect light"
      : selected                 ? "after a point selection"
                                 : "albedo array";
    std::printf("%s: largest change %.0f levels, largest difference from a new mapper %.0f\n",
      what, changed, unlike);
    ok = Check(changed > 20.0, std::string(what) + ": the new indirect light is not drawn") && ok;
    ok = Check(unlike <= 1.0, std::string(what) + ": the updated mapper draws unlike a new one") &&
      ok;
  }
  return ok ? 0 : 1;
}
