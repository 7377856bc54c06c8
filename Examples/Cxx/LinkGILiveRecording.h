// Headless modes of linkgi-live: record a frame sequence, and measure frame times with and
// without a global-illumination update in flight.
#pragma once

#include "vtkAlgorithm.h"
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

/// One JSON line: frame times while the scene is static (no update in flight) and while it
/// changes every frame (an update always in flight), and the completed updates per second.
/// Busy frames are split into the pipeline update on the render thread (the scene source and
/// the filter's RequestData, which hands the scene over and returns) and the rendering.
inline int Benchmark(vtkRenderWindow* window, vtkGlobalIlluminationFilter* gi,
  vtkAlgorithm* shown, const std::function<void(double, bool)>& setTime, const char* scene,
  bool moveLight)
{
  using clock = std::chrono::steady_clock;
  window->SetOffScreenRendering(true);
  setTime(0.0, moveLight);
  RenderSettled(window, gi);
  vtkCamera* camera = window->GetRenderers()->GetFirstRenderer()->GetActiveCamera();
  const int frames = 120;
  std::vector<double> idle, busy, busyPipeline, busyRender;
  for (int f = 0; f < frames; ++f) // static scene: the worker has nothing to do
  {
    const auto t0 = clock::now();
    camera->Azimuth(0.5);
    window->Render();
    idle.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  // BounceRuns counts the solver's completed updates (request ids also count replaced ones).
  const double firstSolved = FieldValue(gi, "LinkGI.BounceRuns");
  const auto start = clock::now();
  for (int f = 0; f < frames; ++f) // the scene changes every frame: always an update in flight
  {
    const auto t0 = clock::now();
    camera->Azimuth(0.5);
    setTime(0.05 * (f + 1), moveLight);
    gi->PollAsynchronousResult();
    shown->Update();
    const auto t1 = clock::now();
    window->Render();
    const auto t2 = clock::now();
    busy.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
    busyPipeline.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    busyRender.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
  }
  const double seconds = std::chrono::duration<double>(clock::now() - start).count();
  const double updates = FieldValue(gi, "LinkGI.BounceRuns") - firstSolved;
  const FrameStats a = Summarize(idle), b = Summarize(busy), p = Summarize(busyPipeline),
                   r = Summarize(busyRender);
  std::printf("{\"scene\":\"%s\",\"change\":\"%s\",\"rays_per_vertex\":%d,\"frames\":%d,"
              "\"idle_ms_median\":%.2f,\"idle_ms_p95\":%.2f,\"busy_ms_median\":%.2f,"
              "\"busy_ms_p95\":%.2f,\"busy_ms_max\":%.2f,\"busy_pipeline_ms_median\":%.2f,"
              "\"busy_render_ms_median\":%.2f,\"busy_render_ms_max\":%.2f,"
              "\"busy_over_idle_median\":%.3f,\"busy_render_over_idle_median\":%.3f,"
              "\"updates_per_s\":%.2f}\n",
    scene, moveLight ? "moving light" : "deforming mesh", gi->GetRaysPerVertex(), frames,
    a.median, a.p95, b.median, b.p95, b.max, p.median, r.median, r.max, b.median / a.median,
    r.median / a.median, updates / seconds);
  return 0;
}
}
