// vtkGlobalIlluminationFilter under faults: a light added and removed while an asynchronous
// update runs, and an abort asked for by another thread during a synchronous update. What
// the output shows is always one complete request's result, never a mix, and the previous
// output survives an abort.
#include "FilterTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationSceneSource.h"
#include "vtkLightCollection.h"
#include "vtkObject.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

using namespace linkgi_test;

namespace
{
/// The Cornell box and its light, through a filter (asynchronous or not).
struct Box
{
  vtkNew<vtkGlobalIlluminationSceneSource> source;
  vtkNew<vtkGlobalIlluminationFilter> filter;
  vtkSmartPointer<vtkLight> light;

  explicit Box(bool asynchronous)
  {
    vtkNew<vtkLightCollection> lights;
    this->source->CreateLights(lights);
    lights->InitTraversal();
    this->light = lights->GetNextItem();
    this->filter->SetInputConnection(this->source->GetOutputPort());
    this->filter->SetAlbedoArrayName("Albedo");
    this->filter->SetRaysPerVertex(16);
    this->filter->SetAsynchronous(asynchronous);
    this->filter->AddLight(this->light);
  }
};

/// A second light beside the box's own.
vtkSmartPointer<vtkLight> SecondLight()
{
  const double position[3] = { 0.2, 0.4, 0.3 }, focal[3] = { 0.0, 0.0, 0.0 };
  return MakeLight(position, focal, 0.5);
}

/// Whether point array `name` of `a` and `b` are bitwise equal.
bool Same(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  vtkDataArray* x = PointArray(a, name);
  vtkDataArray* y = PointArray(b, name);
  if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (x->GetComponent(i, c) != y->GetComponent(i, c))
      {
        return false;
      }
    }
  }
  return true;
}

bool SameResult(vtkPolyData* a, vtkPolyData* b)
{
  return Same(a, b, "DirectIrradiance") && Same(a, b, "IndirectIrradiance");
}
}

TEST(FilterFaults, ALightAddedAndRemovedDuringAnAsynchronousUpdate)
{
  // Request 1: the box's light. Request 2 adds a second light, request 3 (at once, while 2
  // runs or waits) removes it again. Every result shown on the way is exactly the
  // synchronous result of its own request's lights, and the last one shown is request 3's.
  Box one(false), two(false);
  two.filter->AddLight(SecondLight());
  one.filter->Update();
  two.filter->Update();
  ASSERT_FALSE(SameResult(one.filter->GetOutput(), two.filter->GetOutput()));

  Box async(true);
  async.filter->Update();
  vtkSmartPointer<vtkLight> second = SecondLight();
  async.filter->AddLight(second);
  async.filter->Update();
  async.filter->RemoveLight(second);
  async.filter->Update();
  second->SetPosition(9, 9, 9); // a change to a removed light is no change to the filter
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
  double shown = 0;
  while (shown != 3 && std::chrono::steady_clock::now() < deadline)
  {
    if (!async.filter->PollAsynchronousResult())
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    async.filter->Update();
    vtkPolyData* out = async.filter->GetOutput();
    shown = Stat(out, "ShownRequest");
    ASSERT_TRUE(shown >= 1 && shown <= 3) << shown;
    EXPECT_TRUE(SameResult(out, (shown == 2 ? two : one).filter->GetOutput()))
      << "request " << shown << " shows another request's light";
  }
  EXPECT_EQ(shown, 3.0);
  EXPECT_EQ(Stat(async.filter->GetOutput(), "Pending"), 0.0);
}

TEST(FilterFaults, AnAbortFromAnotherThreadKeepsThePreviousOutput)
{
  // A synchronous update after the light moved: once it reports progress it waits until
  // another thread has called SetAbortExecute. The output is then the previous one, with a
  // warning that says so, and the next update is exactly a fresh filter's.
  Box box(false);
  box.filter->Update();
  vtkNew<vtkPolyData> before;
  before->DeepCopy(box.filter->GetOutput());

  double p[3];
  box.light->GetPosition(p);
  box.light->SetPosition(p[0] + 0.1, p[1] - 0.1, p[2]);
  std::atomic<bool> flags[2]; // reached the progress report, abort requested
  flags[0] = false;
  flags[1] = false;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(flags);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* flags, void*) {
    auto* f = static_cast<std::atomic<bool>*>(flags);
    if (!f[0].exchange(true))
    {
      while (!f[1])
      {
        std::this_thread::yield();
      }
    }
  });
  box.filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
  vtkNew<vtkCallbackCommand> onWarning; // the abort's warning, counted instead of printed
  int warnings = 0;
  onWarning->SetClientData(&warnings);
  onWarning->SetCallback([](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  box.filter->AddObserver(vtkCommand::WarningEvent, onWarning);

  std::thread worker([&] { box.filter->Update(); });
  std::thread requester([&] {
    while (!flags[0])
    {
      std::this_thread::yield();
    }
    box.filter->SetAbortExecute(1);
    flags[1] = true;
  });
  requester.join();
  worker.join();
  EXPECT_EQ(warnings, 1);
  EXPECT_TRUE(SameResult(box.filter->GetOutput(), before));

  box.filter->RemoveObserver(onProgress);
  box.filter->SetAbortExecute(0);
  box.filter->Modified();
  box.filter->Update();
  Box fresh(false);
  fresh.light->SetPosition(p[0] + 0.1, p[1] - 0.1, p[2]);
  fresh.filter->Update();
  EXPECT_TRUE(SameResult(box.filter->GetOutput(), fresh.filter->GetOutput()));
  EXPECT_FALSE(SameResult(box.filter->GetOutput(), before));
}
