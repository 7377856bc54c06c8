// Headless modes of linkgi-live: record a frame sequence, and measure frame times with and
// without a global-illumination update in flight.
#pragma once

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGlobalIlluminationFilter.h"
#include "vtkImageAppend.h"
#include "vtkImageResize.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkCamera.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <vector>

namespace linkgi_live
{
inline double FieldValue(vtkGlobalIlluminationFilter* gi, const char* name)
{
  vtkDataArray* a = gi->GetOutput()->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : -1.0;
}

/// Renders until the filter shows the result of its newest request (headless use only).
inline void RenderSettled(vtkRenderWindow* window, vtkGlobalIlluminationFilter* gi)
{
  window->Render();
  for (int i = 0; i < 20000 && FieldValue(gi, "LinkGI.Pending") != 0.0; ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (gi->PollAsynchronousResult())
    {
      window->Render();
    }
  }
}

/// Writes DIR/frame_NNN.png for `frames` frames of the animation, each with its own settled
/// solution, and DIR/strip.png with six of them side by side.
inline int Record(vtkRenderWindow* window, vtkGlobalIlluminationFilter* gi, const std::string& dir,
  int frames, const std::function<void(double)>& setTime)
{
  ::mkdir(dir.c_str(), 0755);
  window->SetOffScreenRendering(true);
  vtkNew<vtkImageAppend> strip;
  strip->SetAppendAxis(0);
  const int every = std::max(1, frames / 6);
  for (int f = 0; f < frames; ++f)
  {
    setTime(f * 6.2832 / frames);
    RenderSettled(window, gi);
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->Update();
    char name[64];
    std::snprintf(name, sizeof(name), "/frame_%03d.png", f);
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName((dir + name).c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    if (f % every == 0 && strip->GetNumberOfInputConnections(0) < 6)
    {
      vtkNew<vtkImageResize> small;
      small->SetInputConnection(grab->GetOutputPort());
      small->SetOutputDimensions(240, 240, 1);
      small->Update();
      strip->AddInputData(small->GetOutput());
    }
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName((dir + "/strip.png").c_str());
  writer->SetInputConnection(strip->GetOutputPort());
  writer->Write();
  std::printf("wrote %d frames and %s/strip.png\n", frames, dir.c_str());
  return 0;
}

struct FrameStats
{
  double median = 0, p95 = 0, max = 0;
};

inline FrameStats Summarize(std::vector<double> ms)
{
  std::sort(ms.begin(), ms.end());
  return { ms[ms.size() / 2], ms[ms.size() * 95 / 100], ms.back() };
}

/// Frame times of `frames` rendered frames; `step(f)` changes the scene before frame f.
inline std::vector<double> TimeFrames(vtkRenderWindow* window, int frames,
  const std::function<void(int)>& step)
{
  using clock = std::chrono::steady_clock;
  vtkCamera* camera = window->GetRenderers()->GetFirstRenderer()->GetActiveCamera();
  std::vector<double> ms;
  for (int f = 0; f < frames; ++f)
  {
    const auto t0 = clock::now();
    camera->Azimuth(0.5);
    step(f);
    window->Render();
    ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  return ms;
}

/// One JSON line: frame times while the scene animates (the torso deforms or the light
/// moves, so shadow maps re-render every frame) without global illumination (the mapper
/// fed straight from the source, `setGi(false)`), and the same animation with the
/// asynchronous filter, which always has an update in flight; plus the updates per second.
inline int Benchmark(vtkRenderWindow* window, vtkGlobalIlluminationFilter* gi,
  const std::function<void(double, bool)>& setTime, const std::function<void(bool)>& setGi,
  const char* scene, bool moveLight)
{
  window->SetOffScreenRendering(true);
  setGi(true);
  setTime(0.0, moveLight);
  RenderSettled(window, gi);
  const int frames = 120;
  setGi(false);
  const std::vector<double> without =
    TimeFrames(window, frames, [&](int f) { setTime(0.05 * (f + 1), moveLight); });
  setGi(true);
  // BounceRuns counts the solver's completed updates (request ids also count replaced ones).
  window->Render();
  const double firstSolved = FieldValue(gi, "LinkGI.BounceRuns");
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> with = TimeFrames(window, frames, [&](int f) {
    setTime(0.05 * (f + 1), moveLight);
    gi->PollAsynchronousResult();
  });
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double updates = FieldValue(gi, "LinkGI.BounceRuns") - firstSolved;
  const FrameStats a = Summarize(without), b = Summarize(with);
  std::printf("{\"scene\":\"%s\",\"change\":\"%s\",\"rays_per_vertex\":%d,\"frames\":%d,"
              "\"without_gi_ms_median\":%.2f,\"without_gi_ms_p95\":%.2f,"
              "\"with_gi_ms_median\":%.2f,\"with_gi_ms_p95\":%.2f,\"with_gi_ms_max\":%.2f,"
              "\"with_over_without_median\":%.3f,\"updates_per_s\":%.2f}\n",
    scene, moveLight ? "moving light" : "deforming mesh", gi->GetRaysPerVertex(), frames,
    a.median, a.p95, b.median, b.p95, b.max, b.median / a.median, updates / seconds);
  return 0;
}
}
