// vtkGlobalIlluminationMapper under MPI (mpirun -np 2): rank 0 holds a block, rank 1 the
// floor under it, each renders its own partition. With the shading's GlobalCasters
// gathered, rank 1's floor shows the block's shadow; without them (the mapper alone) it
// does not. Rank 0 checks that the floor's triangles lie in its shadow maps' bounds: the
// block itself is not shadowed by the floor below it.
#include "RenderingTestUtilities.h"

#include "vtkGlobalIlluminationGlobalCasters.h"
#include "vtkMPIController.h"
#include "vtkTriangleFilter.h"

namespace
{
using namespace linkgi_test;

vtkSmartPointer<vtkPolyData> Plane(
  const double o[3], const double p1[3], const double p2[3], int resolution)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(o[0], o[1], o[2]);
  plane->SetPoint1(p1[0], p1[1], p1[2]);
  plane->SetPoint2(p2[0], p2[1], p2[2]);
  plane->SetResolution(resolution, resolution);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

/// The block x, y in [-0.25, 0.25], z in [0.3, 0.8] (faces outward) or the floor z = 0.
vtkSmartPointer<vtkPolyData> Partition(int rank)
{
  if (rank == 1)
  {
    const double o[3] = { -1.5, -1.5, 0 }, p1[3] = { 1.5, -1.5, 0 }, p2[3] = { -1.5, 1.5, 0 };
    return Plane(o, p1, p2, 40);
  }
  const double l = -0.25, h = 0.25, z0 = 0.3, z1 = 0.8;
  const double faces[6][3][3] = { { { l, l, z0 }, { l, h, z0 }, { h, l, z0 } },
    { { l, l, z1 }, { h, l, z1 }, { l, h, z1 } }, { { l, l, z0 }, { h, l, z0 }, { l, l, z1 } },
    { { l, h, z0 }, { l, h, z1 }, { h, h, z0 } }, { { l, l, z0 }, { l, l, z1 }, { l, h, z0 } },
    { { h, l, z0 }, { h, h, z0 }, { h, l, z1 } } };
  vtkNew<vtkAppendPolyData> append;
  for (const auto& f : faces)
  {
    append->AddInputData(Plane(f[0], f[1], f[2], 6));
  }
  append->Update();
  return append->GetOutput();
}

/// The grey value where the world point `p` is drawn.
double At(vtkRenderer* renderer, vtkImageData* image, const double p[3])
{
  renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  return Pixel(image, static_cast<int>(std::lround(d[0])), static_cast<int>(std::lround(d[1])), 0);
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  bool ok = controller->GetNumberOfProcesses() == 2;

  vtkSmartPointer<vtkPolyData> partition = Partition(rank);
  vtkNew<vtkGlobalIlluminationGlobalCasters> casters;
  casters->Gather(partition);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  const double position[3] = { 0.5, 0.3, 2.0 }, focal[3] = { 0, 0, 0 }, white[3] = { 1, 1, 1 };
  renderer->AddLight(SceneLight(position, focal, 180.0, 4.0, white));
  vtkGlobalIlluminationMapper* mapper = AddMappedActor(renderer, partition);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, -3.0, 3.2);
  camera->SetFocalPoint(0.0, 0.0, 0.2);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(30);
  renderer->ResetCameraClippingRange(-1.5, 1.5, -1.5, 1.5, 0.0, 0.8);
  auto window = MakeWindow(320, 320);
  window->AddRenderer(renderer);

  // The light casts the block's shadow over about x in [-0.7, 0.2], y in [-0.6, 0.2].
  const double shadowPoint[3] = { -0.5, -0.3, 0.0 }, litPoint[3] = { 1.0, 1.0, 0.0 };
  const double blockTop[3] = { 0.0, 0.0, 0.8 };
  double shadowed[2], lit[2], top[2];
  for (int withCasters = 0; withCasters < 2; ++withCasters)
  {
    mapper->GetShading()->SetGlobalCasters(withCasters ? casters.Get() : nullptr);
    window->Render();
    vtkSmartPointer<vtkImageData> image = Capture(window);
    shadowed[withCasters] = At(renderer, image, shadowPoint);
    lit[withCasters] = At(renderer, image, litPoint);
    top[withCasters] = At(renderer, image, blockTop);
  }
  if (rank == 1)
  {
    std::printf("rank 1: floor in the shadow %g / %g (without / with the casters), lit %g\n",
      shadowed[0], shadowed[1], lit[1]);
    ok = Check(lit[1] > 40.0, "rank 1: the floor is lit") && ok;
    ok = Check(shadowed[0] > 0.5 * lit[0], "rank 1: without the casters no shadow") && ok;
    ok = Check(shadowed[1] < 0.25 * lit[1], "rank 1: with them, rank 0's block shadows it") && ok;
    ok = Check(casters->GetNumberOfTriangles() == 432, "rank 1 received the block's 432") && ok;
  }
  else
  {
    std::printf("rank 0: block top %g / %g (without / with the casters)\n", top[0], top[1]);
    ok = Check(top[1] > 40.0 && std::abs(top[1] - top[0]) <= 2.0,
           "rank 0: the block's top stays lit with the floor below it as a caster") &&
      ok;
    ok = Check(casters->GetNumberOfTriangles() == 3200, "rank 0 received the floor's 3200") && ok;
  }
  int failed = ok ? 0 : 1, anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  window->Finalize();
  controller->Finalize();
  return anyFailed;
}
