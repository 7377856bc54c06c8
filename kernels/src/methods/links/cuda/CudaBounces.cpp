// The bounce stage of the CUDA engine: every partition (GPU) gathers its own rows of each
// bounce from the whole radiance vector, and the rows it computed go to the other
// partitions between bounces (peer copies over NVLink, or staged by the driver without peer
// access). Smoothing reads neighbours, so the first partition gathers E_ind and E_env for it.
#include "methods/links/cuda/EngineDevice.h"

#include "shared/Bounce.h"

#include <chrono>
#include <cmath>

namespace linkgi::cuda
{
namespace
{
using engine::msSince;
}

void Engine::exchange(Rgba* (*of)(EngineDevice&), bool toAll)
{
  if (devices.size() < 2)
  {
    return;
  }
  for (const auto& d : devices)
  {
    d->use();
    LINKGI_CUDA_CHECK(cudaEventRecord(d->ready, d->stream));
  }
  for (std::size_t q = 0; q < (toAll ? devices.size() : 1); ++q)
  {
    EngineDevice& to = *devices[q];
    to.use();
    for (std::size_t p = 0; p < devices.size(); ++p)
    {
      EngineDevice& from = *devices[p];
      if (p == q || from.blocks.empty())
      {
        continue;
      }
      // Pulled on the receiver's stream: after its own kernels that read the old values,
      // and before the next that read the new ones.
      LINKGI_CUDA_CHECK(cudaStreamWaitEvent(to.stream, from.ready, 0));
      for (const MatrixBlock& b : from.blocks)
      {
        LINKGI_CUDA_CHECK(cudaMemcpyPeerAsync(of(to) + b.first, to.id, of(from) + b.first, from.id,
          std::size_t(b.count) * sizeof(Rgba), to.stream));
      }
    }
  }
}

void Engine::bounceAndFinish(const engine::StageContext& c)
{
  using clock = std::chrono::steady_clock;
  const Scene& s = c.scene;
  const SolverOptions& options = c.options;
  Solution& solution = c.solution;
  EngineDevice& d0 = *devices[0];
  const Elements elements{ s.vertexCount(), options.twoSided };
  const Index ne = Index(elements.count());
  std::vector<Rgba> texels;
  for (const Vec3f& r : environmentTexelRadiance(s.environment))
  {
    texels.push_back(toRgba(r));
  }
  const bool shading = (c.changes & (engine::kTopology | engine::kAlbedo | engine::kEmission)) != 0;
  // Every partition computes its rows of each bounce from the whole radiance vector: E_env
  // and the start for its rows, then after each bounce the rows move between partitions.
  // Albedo and emission go up once, to the first partition, with room for the outputs'
  // download; the others copy them, and E_d of the light links, from it.
  d0.use();
  d0.staging.begin((shading ? PinnedStaging::room(s.albedo.size() * sizeof(Vec3f)) +
      PinnedStaging::room(s.emission.size() * sizeof(Vec3f)) : 0) +
    PinnedStaging::room(3 * std::size_t(ne) * sizeof(Vec3f)));
  if (shading)
  {
    d0.staging.upload(d0.albedo, s.albedo, d0.stream);
    d0.staging.upload(d0.emission, s.emission, d0.stream);
  }
  LINKGI_CUDA_CHECK(cudaEventRecord(d0.ready, d0.stream)); // after the light links' E_d
  for (const auto& dp : devices)
  {
    EngineDevice& d = *dp;
    if (&d != &d0)
    {
      if (shading)
      {
        copyFrom(d0, d, &EngineDevice::albedo);
        copyFrom(d0, d, &EngineDevice::emission);
      }
      copyFrom(d0, d, &EngineDevice::direct);
      copyFrom(d0, d, &EngineDevice::nodeDirect);
    }
    d.use();
    d.texelRadiance.upload(texels, d.stream);
    for (GPUBuffer<Rgba>* b : { &d.envIrradiance, &d.fixedIrradiance, &d.indirect })
    {
      b->resize(ne);
    }
    for (GPUBuffer<Rgba>& b : d.radiance)
    {
      b.resize(ne + detail.columns(options.twoSided)); // the detail nodes' after the elements'
    }
  }
  BounceParams b;
  b.elements = ne;
  b.vertexCount = Index(s.vertexCount());
  b.emission = nullptr;
  const auto paramsOf = [&b, &s](EngineDevice& d) {
    BounceParams p = b;
    p.direct = d.direct.data();
    p.environment = d.envIrradiance.data();
    p.albedo = d.albedo.data();
    p.emission = s.emission.empty() ? nullptr : d.emission.data();
    return p;
  };
  // Threads per row from the whole matrices: each row sums in one order however the rows
  // are split between batches and GPUs, so the result does not depend on the split.
  Offset transportEntries = 0, environmentEntries = 0;
  for (const auto& d : devices)
  {
    for (const MatrixBlock& m : d->blocks)
    {
      transportEntries += m.transport.nonZeros;
      environmentEntries += m.environment.nonZeros;
    }
  }
  const int transportLanes = lanesForRows(transportEntries, std::uint64_t(ne));
  const int environmentLanes = lanesForRows(environmentEntries, std::uint64_t(ne));
  for (const auto& dp : devices)
  {
    EngineDevice& d = *dp;
    d.use();
    const BounceParams p = paramsOf(d);
    for (const MatrixBlock& m : d.blocks)
    {
      gatherRgb(m.environment.view(m.first, environmentLanes), d.texelRadiance.data(), d.envIrradiance.data(), d.stream);
      startBounces(p, m.first, m.count, d.fixedIrradiance.data(), d.radiance[0].data(), d.stream);
    }
  }
  exchange([](EngineDevice& d) { return d.radiance[0].data(); }, true);
  // The detail nodes' radiance from the whole vector of the elements', on every partition.
  const auto nodeRadiance = [&](int which) {
    for (const auto& dp : devices)
    {
      EngineDevice& d = *dp;
      d.use();
      detailRadiance(detailParams(d, options.twoSided), ne, b.vertexCount, d.direct.data(), d.albedo.data(),
        d.nodeDirect.data(), d.radiance[which].data(), d.stream);
    }
  };
  nodeRadiance(0);
  for (std::uint32_t i = 0; i < options.bounces; ++i)
  {
    const bool last = i + 1 == options.bounces;
    c.check(double(i) / options.bounces);
    for (const auto& dp : devices)
    {
      EngineDevice& d = *dp;
      d.use();
      const BounceParams p = paramsOf(d);
      for (const MatrixBlock& m : d.blocks)
      {
        bounce(m.transport.view(m.first, transportLanes), p, d.fixedIrradiance.data(), d.radiance[i % 2].data(),
          d.indirect.data(), last ? nullptr : d.radiance[(i + 1) % 2].data(), d.stream);
      }
    }
    if (!last)
    {
      exchange(i % 2 ? +[](EngineDevice& d) { return d.radiance[0].data(); }
                     : +[](EngineDevice& d) { return d.radiance[1].data(); },
        true);
      nodeRadiance(int((i + 1) % 2));
    }
  }
  // Smoothing reads neighbours' values: the first partition gathers E_ind and E_env.
  exchange([](EngineDevice& d) { return d.envIrradiance.data(); }, false);
  if (options.bounces > 0)
  {
    exchange([](EngineDevice& d) { return d.indirect.data(); }, false);
  }
  const auto t = clock::now();
  d0.use();
  FinishParams f;
  f.bounce = paramsOf(d0);
  f.indirect = options.bounces > 0 ? d0.indirect.data() : nullptr;
  f.smoothing = smoothingOn(options);
  f.cosFeatureAngle = std::cos(options.featureAngleDegrees * (kPi / 180.f));
  f.neighbourOffsets = d0.topology.neighbourOffsets.data();
  f.neighbours = d0.topology.neighbours.data();
  f.normals = d0.normals.data();
  d0.output.resize(3 * std::size_t(ne));
  finish(f, d0.output.data(), d0.stream);
  // The three outputs in one download through pinned memory.
  const std::size_t bytes = 3 * std::size_t(ne) * sizeof(Vec3f);
  const Vec3f* staged = static_cast<const Vec3f*>(d0.staging.download(d0.output.data(), bytes, d0.stream));
  solution.direct.resize(ne);
  solution.indirect.resize(ne);
  solution.radiance.resize(ne);
  for (const auto& d : devices)
  {
    d->sync();
  }
  for (std::size_t i = 0; i < 3; ++i)
  {
    std::vector<Vec3f>& to = i == 0 ? solution.direct : i == 1 ? solution.indirect : solution.radiance;
    PinnedStaging::copy(to.data(), staged + i * ne, ne * sizeof(Vec3f));
  }
  if (smoothingOn(options))
  {
    c.part("Smoothing", msSince(t)); // with the read-back, as on the CPU
  }
}
}
