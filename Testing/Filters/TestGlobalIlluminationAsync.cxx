// vtkGlobalIlluminationFilter in asynchronous mode: RequestData never waits for the solver.
#include "FilterTestUtilities.h"

#include "vtkGlobalIlluminationFilter.h"
#include "vtkGlobalIlluminationSceneSource.h"
#include "vtkLightCollection.h"

#include "linkgi/AsyncSolver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <utility>
#include <vector>

using namespace linkgi_test;

namespace
{
struct CornellPipeline
{
  vtkNew<vtkGlobalIlluminationSceneSource> source;
  vtkNew<vtkLightCollection> lights;
  vtkNew<vtkGlobalIlluminationFilter> filter;

  explicit CornellPipeline(bool asynchronous)
  {
    this->source->CreateLights(this->lights);
    this->filter->SetInputConnection(this->source->GetOutputPort());
    this->filter->SetAlbedoArrayName("Albedo");
    this->filter->SetRaysPerVertex(64);
    this->filter->SetAsynchronous(asynchronous);
    this->lights->InitTraversal();
    this->filter->AddLight(this->lights->GetNextItem());
  }

  /// Polls like a render loop until a new result is shown (or 600 s pass: minutes under
  /// ThreadSanitizer on a loaded machine).
  bool WaitForResult()
  {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
    while (std::chrono::steady_clock::now() < deadline)
    {
      if (this->filter->PollAsynchronousResult())
      {
        this->filter->Update();
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }
};

void ExpectSameArray(vtkPolyData* a, vtkPolyData* b, const char* name)
{
  vtkDataArray* x = PointArray(a, name);
  vtkDataArray* y = PointArray(b, name);
  ASSERT_TRUE(x && y);
  ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples());
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(x->GetComponent(i, c), y->GetComponent(i, c)) << name << " " << i;
    }
  }
}
}

TEST(GlobalIlluminationAsync, ReturnsAtOnceThenDeliversTheSynchronousResult)
{
  CornellPipeline async(true), sync(false);
  async.filter->Update();
  vtkPolyData* first = async.filter->GetOutput();
  // Nothing solved yet: the arrays exist and are black, and the worker is busy.
  ASSERT_NE(PointArray(first, "Radiance"), nullptr);
  EXPECT_EQ(Stat(first, "ShownRequest"), 0.0);
  EXPECT_EQ(Stat(first, "Pending"), 1.0);
  EXPECT_EQ(PointArray(first, "Radiance")->GetRange(0)[1], 0.0);

  ASSERT_TRUE(async.WaitForResult());
  sync.filter->Update();
  ExpectSameArray(async.filter->GetOutput(), sync.filter->GetOutput(), "DirectIrradiance");
  ExpectSameArray(async.filter->GetOutput(), sync.filter->GetOutput(), "IndirectIrradiance");
  EXPECT_EQ(Stat(async.filter->GetOutput(), "ShownRequest"), 1.0);
  // Polling again finds nothing new: no endless re-execution.
  EXPECT_FALSE(async.filter->PollAsynchronousResult());
  async.filter->Update();
  EXPECT_FALSE(async.filter->PollAsynchronousResult());
}

TEST(GlobalIlluminationAsync, MovingALightShowsTheOldResultUntilTheNewOneArrives)
{
  CornellPipeline async(true);
  async.filter->Update();
  ASSERT_TRUE(async.WaitForResult());
  const double before = Stat(async.filter->GetOutput(), "LinkBuilds");
  vtkLight* light = async.filter->GetLight(0);
  double p[3];
  light->GetPosition(p);
  light->SetPosition(p[0] + 0.1, p[1] - 0.1, p[2]);
  // held: an array freed by a later update could be replaced by one at its address
  vtkSmartPointer<vtkDataArray> shown = PointArray(async.filter->GetOutput(), "IndirectIrradiance");
  async.filter->Update(); // returns at once with the previous, complete result
  EXPECT_EQ(Stat(async.filter->GetOutput(), "ShownRequest"), 1.0);
  // ... as the same arrays, so that a mapper drawing them uploads nothing again
  EXPECT_EQ(PointArray(async.filter->GetOutput(), "IndirectIrradiance"), shown);
  ASSERT_TRUE(async.WaitForResult());
  EXPECT_EQ(Stat(async.filter->GetOutput(), "ShownRequest"), 2.0);
  EXPECT_NE(PointArray(async.filter->GetOutput(), "IndirectIrradiance"), shown);
  EXPECT_EQ(Stat(async.filter->GetOutput(), "LinkBuilds"), before); // light only: no relink
}

TEST(GlobalIlluminationAsync, ProgressiveDrawsACoarseStageThenTheSynchronousResult)
{
  // The first update of a mesh: nothing measured yet, so a coarse stage (9 of the 64 rays)
  // is drawn first, then the final stage, which is the synchronous result exactly. A light
  // move that the link method answers quickly is drawn as its final solution alone.
  linkgi::AsyncSolver::forgetMeasurements(); // as in a new process: the final's time unknown
  CornellPipeline async(true), sync(false);
  async.filter->ProgressiveOn();
  async.filter->Update();
  std::vector<std::pair<double, double>> stages; // (ShownStage, Stages) of each drawn result
  std::vector<double> meanIndirect;
  while (stages.empty() || stages.back().first != stages.back().second)
  {
    ASSERT_TRUE(async.WaitForResult());
    vtkPolyData* out = async.filter->GetOutput();
    stages.emplace_back(Stat(out, "ShownStage"), Stat(out, "Stages"));
    EXPECT_EQ(Stat(out, "ShownRequest"), 1.0);
    double sum = 0.0;
    vtkDataArray* indirect = PointArray(out, "IndirectIrradiance");
    for (vtkIdType i = 0; i < indirect->GetNumberOfTuples(); ++i)
    {
      sum += indirect->GetComponent(i, 1);
    }
    meanIndirect.push_back(sum / double(indirect->GetNumberOfTuples()));
  }
  // WaitForResult may skip a stage the worker replaced before the poll; the first update
  // publishes two, and the drawn ones come in order.
  EXPECT_EQ(stages.back(), std::make_pair(2.0, 2.0));
  for (std::size_t i = 1; i < stages.size(); ++i)
  {
    EXPECT_GT(stages[i].first, stages[i - 1].first);
  }
  if (stages.size() == 2)
  {
    EXPECT_NEAR(meanIndirect[0], meanIndirect[1], 0.3 * meanIndirect[1]); // the same light, coarser
  }
  sync.filter->Update();
  ExpectSameArray(async.filter->GetOutput(), sync.filter->GetOutput(), "DirectIrradiance");
  ExpectSameArray(async.filter->GetOutput(), sync.filter->GetOutput(), "IndirectIrradiance");
  EXPECT_EQ(async.filter->GetAsynchronousStage(), 0); // idle

  // A light move is predicted from the stages the first update measured. Quick is relative
  // to the first stage's budget (four of them): 10 s, which no light move of this box
  // reaches even under ThreadSanitizer on a loaded machine (at the default 0.5 s it once did).
  async.filter->SetProgressiveFirstStageSeconds(10.0);
  vtkLight* light = async.filter->GetLight(0);
  double p[3];
  light->GetPosition(p);
  light->SetPosition(p[0] + 0.1, p[1] - 0.1, p[2]);
  async.filter->Update();
  ASSERT_TRUE(async.WaitForResult());
  EXPECT_EQ(Stat(async.filter->GetOutput(), "ShownRequest"), 2.0);
  EXPECT_EQ(Stat(async.filter->GetOutput(), "Stages"), 1.0) << "a quick light move has no coarse stage";
}
