// vtkGlobalIlluminationCompositeMapper draws a multiblock dataset like
// vtkGlobalIlluminationMapper draws the whole.
// - The Cornell box split in two blocks (its triangles left and right of x = 0.3) must look
//   like the whole box drawn by the single mapper: the blocks share one helper, so they
//   shadow each other, and every block carries its shading arrays.
// - A third block without any shading array (a sphere) is drawn with the actor's colour as
//   its albedo and no indirect light, and casts a shadow onto the other blocks.
#include "RenderingTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkMultiBlockDataSet.h"

namespace
{
using namespace linkgi_test;

/// The box's triangles in two blocks, left and right of x = 0.3; both keep all points.
vtkSmartPointer<vtkMultiBlockDataSet> SplitInTwo(vtkPolyData* box)
{
  vtkNew<vtkCellArray> halves[2];
  auto it = vtk::TakeSmartPointer(box->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    halves[box->GetPoint(ids[0])[0] < 0.3 ? 0 : 1]->InsertNextCell(n, ids);
  }
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  blocks->SetNumberOfBlocks(2);
  for (int i = 0; i < 2; ++i)
  {
    vtkNew<vtkPolyData> half;
    half->SetPoints(box->GetPoints());
    half->GetPointData()->ShallowCopy(box->GetPointData());
    half->SetPolys(halves[i]);
    blocks->SetBlock(i, half);
  }
  return blocks;
}

vtkSmartPointer<vtkRenderer> Scene(vtkRenderer* lighting, vtkMapper* mapper, double exposure)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(1, 0, 1);
  AddLights(renderer, lighting->GetLights());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  CornellCamera(renderer);
  if (auto* gi = vtkGlobalIlluminationMapper::SafeDownCast(mapper))
  {
    gi->GetShading()->SetToneMappingToHuePreserving();
    gi->GetShading()->SetExposure(exposure);
  }
  if (auto* gi = vtkGlobalIlluminationCompositeMapper::SafeDownCast(mapper))
  {
    gi->GetShading()->SetToneMappingToHuePreserving();
    gi->GetShading()->SetExposure(exposure);
  }
  return renderer;
}
}

int TestGlobalIlluminationCompositeMapper(int, char*[])
{
  vtkNew<vtkRenderer> lighting;
  vtkSmartPointer<vtkPolyData> box = CornellBox(lighting);
  const double exposure = AutoExposure(box->GetPointData()->GetArray("Radiance"));
  auto window = MakeWindow(300, 300);

  vtkNew<vtkGlobalIlluminationMapper> single;
  single->SetInputData(box);
  vtkSmartPointer<vtkImageData> whole = RenderAlone(window, Scene(lighting, single, exposure));
  vtkNew<vtkGlobalIlluminationCompositeMapper> composite;
  vtkSmartPointer<vtkMultiBlockDataSet> blocks = SplitInTwo(box);
  composite->SetInputDataObject(blocks);
  vtkSmartPointer<vtkRenderer> cutScene = Scene(lighting, composite, exposure);
  // The colour of blocks without an albedo array (vtkCompositePolyDataMapper2 takes the
  // actor's colour when it first builds its per-block values).
  cutScene->GetActors()->GetLastActor()->GetProperty()->SetDiffuseColor(0.1, 0.8, 0.1);
  vtkSmartPointer<vtkImageData> cut = RenderAlone(window, cutScene);

  double worst = 0.0, total = 0.0;
  int differing = 0;
  const int n = whole->GetNumberOfPoints();
  for (int p = 0; p < n; ++p)
  {
    double d = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      d = std::max(d,
        std::abs(whole->GetPointData()->GetScalars()->GetComponent(p, k) -
          cut->GetPointData()->GetScalars()->GetComponent(p, k)));
    }
    worst = std::max(worst, d);
    total += d;
    differing += d > 3.0 ? 1 : 0;
  }
  std::printf("two blocks vs the whole: mean difference %.3f levels, %d pixels differ by more "
              "than 3 (largest %.0f), shadow map renders %d\n",
    total / n, differing, worst, composite->GetShadowMapRenderCount());
  bool ok = Check(total / n < 0.2 && differing < n / 500, "the blocks look unlike the whole");
  ok = Check(
         composite->GetShadowMapRenderCount() == 1, "expected one helper, one shadow map render") &&
    ok;

  // A new indirect irradiance on the blocks, as each asynchronous result brings: only the
  // shading attributes are uploaded (the positions are not, so the shadow maps are not
  // rendered again), and the picture is a new mapper's.
  vtkDataArray* indirect = box->GetPointData()->GetArray("IndirectIrradiance");
  vtkNew<vtkFloatArray> brighter;
  brighter->DeepCopy(indirect);
  for (vtkIdType i = 0; i < brighter->GetNumberOfValues(); ++i)
  {
    brighter->SetValue(i, 4.0f * brighter->GetValue(i));
  }
  for (unsigned int b = 0; b < blocks->GetNumberOfBlocks(); ++b)
  {
    vtkPolyData::SafeDownCast(blocks->GetBlock(b))->GetPointData()->AddArray(brighter);
  }
  window->Render(); // the same renderer, its buffers and shadow maps kept
  vtkSmartPointer<vtkImageData> updated = Capture(window);
  const int renders = composite->GetShadowMapRenderCount(); // before RenderAlone releases it
  vtkNew<vtkGlobalIlluminationCompositeMapper> fresh;
  fresh->SetInputDataObject(blocks);
  vtkSmartPointer<vtkRenderer> freshScene = Scene(lighting, fresh, exposure);
  freshScene->GetActors()->GetLastActor()->GetProperty()->SetDiffuseColor(0.1, 0.8, 0.1);
  vtkSmartPointer<vtkImageData> rebuilt = RenderAlone(window, freshScene);
  double changed = 0.0, unlike = 0.0;
  for (int p = 0; p < n; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double u = updated->GetPointData()->GetScalars()->GetComponent(p, k);
      changed = std::max(changed, std::abs(u - cut->GetPointData()->GetScalars()->GetComponent(p, k)));
      unlike = std::max(unlike, std::abs(u - rebuilt->GetPointData()->GetScalars()->GetComponent(p, k)));
    }
  }
  std::printf("new indirect light: largest change %.0f levels, largest difference from a new "
              "mapper %.0f, shadow map renders %d\n",
    changed, unlike, renders);
  ok = Check(changed > 20.0, "the new indirect light is not drawn") && ok;
  ok = Check(unlike <= 1.0, "the updated mapper draws unlike a new one") && ok;
  ok = Check(renders == 1,
         "a new indirect light alone rebuilt the positions (shadow maps rendered again)") &&
    ok;

  // A sphere without shading arrays, hanging over the floor beside the tall block.
  const double centre[3] = { 0.45, 0.15, 0.2 }, radius = 0.04;
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetCenter(centre[0], centre[1], centre[2]);
  sphereSource->SetRadius(radius);
  sphereSource->Update();
  // Direct light only, so that the shadow is not filled in by indirect light.
  composite->GetShading()->SetDisplayModeToDirect();
  vtkSmartPointer<vtkImageData> withoutSphere = RenderAlone(window, cutScene);
  blocks->SetNumberOfBlocks(3);
  blocks->SetBlock(2, sphereSource->GetOutput());
  vtkSmartPointer<vtkImageData> withSphere = RenderAlone(window, cutScene);
  double light[3];
  vtkLight::SafeDownCast(lighting->GetLights()->GetItemAsObject(0))->GetPosition(light);
  vtkNew<vtkCoordinate> coordinate;
  coordinate->SetCoordinateSystemToWorld();
  coordinate->SetValue(centre[0], centre[1] + 0.7 * radius, centre[2] - 0.7 * radius); // lit side
  const int d[2] = { coordinate->GetComputedDisplayValue(cutScene)[0],
    coordinate->GetComputedDisplayValue(cutScene)[1] };
  const double r = Pixel(withSphere, d[0], d[1], 0), g = Pixel(withSphere, d[0], d[1], 1);
  const double s = light[1] / (light[1] - centre[1]); // the floor behind the sphere, from the light
  coordinate->SetValue(
    light[0] + s * (centre[0] - light[0]), 0.0, light[2] + s * (centre[2] - light[2]));
  const int* f = coordinate->GetComputedDisplayValue(cutScene);
  const double under = Pixel(withSphere, f[0], f[1], 1),
               before = Pixel(withoutSphere, f[0], f[1], 1);
  std::printf("sphere block: colour (%.0f, %.0f), its shadow on the floor %.0f (was %.0f)\n", r, g,
    under, before);
  ok =
    Check(g > 40.0 && g > 2.0 * r, "the block without arrays is not drawn in the actor's colour") &&
    ok;
  ok = Check(under < 0.3 * before, "the sphere block casts no shadow on the floor") && ok;
  return ok ? 0 : 1;
}
