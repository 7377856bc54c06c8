// A point light's cube shadow map on all six faces.
//
// A point light sits at the centre of a closed room (a cube of half-size 1 whose walls face
// inwards). Six small blocks stand around it, one towards each axis direction and each off
// the axis by a different amount, so that a face drawn flipped or rotated, or looked up
// through the wrong face, would put a shadow elsewhere. Each wall is viewed from the light
// itself (near clipping plane beyond the blocks): seen from there, a shadow covers exactly
// the silhouette of its block, so the pixel where the block's centre projects must be
// dark, and the pixels where its centre would land mirrored in either wall axis must be
// lit. The six views are compared with a baseline too.
#include "RenderingTestUtilities.h"

#include "vtkAppendPolyData.h"
#include "vtkCoordinate.h"
#include "vtkCubeSource.h"
#include "vtkReverseSense.h"

namespace
{
using namespace linkgi_test;

const int Tile = 200;

/// Block centre towards axis `a` (0..2) with sign `s`: half way to the wall, off the axis
/// by 0.2 and 0.1 along the other two axes (in an order that differs per face).
void BlockCentre(int face, double c[3])
{
  const int a = face / 2;
  const double s = face % 2 ? -1.0 : 1.0;
  c[a] = 0.5 * s;
  c[(a + 1) % 3] = face % 2 ? -0.2 : 0.2;
  c[(a + 2) % 3] = 0.1;
}

vtkSmartPointer<vtkPolyData> Room()
{
  vtkNew<vtkCubeSource> room;
  room->SetXLength(2);
  room->SetYLength(2);
  room->SetZLength(2);
  vtkNew<vtkReverseSense> inwards; // walls face the light inside
  inwards->SetInputConnection(room->GetOutputPort());
  inwards->ReverseCellsOn();
  inwards->ReverseNormalsOn();
  vtkNew<vtkAppendPolyData> append;
  append->AddInputConnection(inwards->GetOutputPort());
  for (int face = 0; face < 6; ++face)
  {
    double c[3];
    BlockCentre(face, c);
    vtkNew<vtkCubeSource> block;
    block->SetCenter(c);
    block->SetXLength(0.2);
    block->SetYLength(0.2);
    block->SetZLength(0.2);
    block->Update();
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(block->GetOutput());
    append->AddInputData(copy);
  }
  append->Update();
  return append->GetOutput();
}

/// A renderer in tile `face` looking from the light (the origin) at wall `face`.
vtkSmartPointer<vtkRenderer> View(int face, vtkActor* actor, vtkLight* light)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  const int column = face % 3, row = face / 3;
  renderer->SetViewport(column / 3.0, row / 2.0, (column + 1) / 3.0, (row + 1) / 2.0);
  renderer->AddActor(actor);
  renderer->AddLight(light);
  double focal[3] = { 0, 0, 0 }, up[3] = { 0, 0, 0 };
  focal[face / 2] = face % 2 ? -1.0 : 1.0;
  up[(face / 2 + 1) % 3] = 1.0;
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 0);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  camera->SetViewAngle(90);
  camera->SetClippingRange(0.7, 3.0); // the blocks are nearer: only the walls show
  return renderer;
}

/// Luminance of the pixel where the world point `p` projects in `renderer`.
double LuminanceAt(vtkRenderer* renderer, vtkImageData* image, const double p[3])
{
  vtkNew<vtkCoordinate> coordinate;
  coordinate->SetCoordinateSystemToWorld();
  coordinate->SetValue(p[0], p[1], p[2]);
  const int* d = coordinate->GetComputedDisplayValue(renderer);
  return (Pixel(image, d[0], d[1], 0) + Pixel(image, d[0], d[1], 1) + Pixel(image, d[0], d[1], 2)) /
    3.0;
}

/// The block's shadow is where it should be on wall `face`, and not at mirrored places.
bool ShadowInPlace(int face, vtkRenderer* renderer, vtkImageData* image)
{
  double c[3];
  BlockCentre(face, c);
  const double shadow[3] = { 2 * c[0], 2 * c[1], 2 * c[2] }; // on the wall, seen from the light
  const double inShadow = LuminanceAt(renderer, image, shadow);
  bool ok =
    Check(inShadow < 5.0, "face " + std::to_string(face) + ": no shadow where the block projects");
  for (int k = 1; k <= 2; ++k)
  {
    double mirrored[3] = { shadow[0], shadow[1], shadow[2] };
    mirrored[(face / 2 + k) % 3] *= -1.0;
    const double lit = LuminanceAt(renderer, image, mirrored);
    std::printf(
      "face %d: shadow %.1f, mirrored in axis %d %.1f\n", face, inShadow, (face / 2 + k) % 3, lit);
    ok =
      Check(lit > 60.0, "face " + std::to_string(face) + ": shadow also at a mirrored place") && ok;
  }
  return ok;
}
}

int TestGlobalIlluminationMapperCubeFaces(int argc, char* argv[])
{
  vtkSmartPointer<vtkPolyData> room = Room();
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetAttenuationValues(0, 0, 1); // a lamp: 1/r^2
  light->SetConeAngle(180);
  light->SetPosition(0, 0, 0);
  light->SetFocalPoint(0, 0, -1);

  vtkNew<vtkGlobalIlluminationMapper> mapper;
  mapper->SetInputData(room);
  mapper->GetShading()->SetDisplayModeToDirect();
  mapper->GetShading()->SetToneMappingToLinear();
  mapper->GetShading()->SetExposure(2.0);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);

  auto window = MakeWindow(3 * Tile, 2 * Tile);
  std::vector<vtkSmartPointer<vtkRenderer>> views;
  for (int face = 0; face < 6; ++face)
  {
    views.push_back(View(face, actor, light));
    window->AddRenderer(views.back());
  }
  window->Render();
  vtkSmartPointer<vtkImageData> image = Capture(window);
  bool ok =
    Check(mapper->GetShadowMapRenderCount() == 1, "the six views did not share one shadow map");
  for (int face = 0; face < 6; ++face)
  {
    ok = ShadowInPlace(face, views[face], image) && ok;
  }
  return (CompareWithBaseline(argc, argv, window) == 0 && ok) ? 0 : 1;
}
