#include "shared/Bounce.h"

#include "linkgi/Error.h"

namespace linkgi
{
void gatherRgb(const SparseMatrix& m, const Vec3f* x, Vec3f* y)
{
  gatherRgb(m.view(), x, y);
}

namespace
{
void gatherRows(const CsrRows& m, const Vec3f* x, Vec3f* y, std::size_t begin, std::size_t end)
{
  for (std::size_t r = begin; r < end; ++r)
  {
    Vec3f sum(0.f);
    for (Offset i = m.rowOffsets[r] - m.firstEntry; i < m.rowOffsets[r + 1] - m.firstEntry; ++i)
    {
      sum += x[m.columns[i]] * m.weights[i];
    }
    y[r] = sum;
  }
}
}

void gatherRgb(const CsrRows& m, const Vec3f* x, Vec3f* y)
{
  parallelRanges(m.rows, 256, [&](std::size_t begin, std::size_t end) { gatherRows(m, x, y, begin, end); });
}

std::vector<Vec3f> iterateBounces(const SparseMatrix& transport, const BounceInputs& inputs,
  std::uint32_t bounces, const ProgressCallback& progress,
  const std::function<void(std::vector<Vec3f>&)>& exchange)
{
  const std::size_t n = inputs.fixedIrradiance.size();
  std::vector<Vec3f> indirect(n, Vec3f(0.f)), radiance(n + inputs.extraColumns);
  for (std::uint32_t b = 0; b < bounces; ++b)
  {
    if (progress && !progress("bounces", double(b) / bounces))
    {
      throw Aborted();
    }
    parallelRanges(n, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t e = begin; e < end; ++e)
      {
        radiance[e] = outgoingRadiance(inputs.albedo[e], inputs.fixedIrradiance[e], indirect[e],
          inputs.emission.empty() ? Vec3f(0.f) : inputs.emission[e]);
      }
    });
    if (inputs.extraColumns)
    {
      inputs.extraRadiance(radiance.data());
    }
    // The gather is the bounce's whole cost (tens of ms per bounce at 100k vertices): it
    // checks for an abort in slices, so that cancel() or a starved background update stops
    // within milliseconds of work rather than a bounce.
    const CsrRows rows = transport.view();
    const ProgressCallback sliced = progress
      ? ProgressCallback([&progress, b, bounces](const char* stage, double f) {
          return progress(stage, (b + f) / bounces);
        })
      : ProgressCallback();
    parallelFor("bounces", rows.rows, 256,
      [&](std::size_t begin, std::size_t end) { gatherRows(rows, radiance.data(), indirect.data(), begin, end); },
      sliced);
    if (exchange)
    {
      exchange(indirect); // other processes' rows gathered zero here
    }
  }
  return indirect;
}

std::vector<Vec3f> smoothFeatureAware(const std::vector<Vec3f>& values, const Topology& topology,
  const std::vector<Vec3f>& normals, const Elements& elements, float cosFeatureAngle)
{
  std::vector<Vec3f> out(values.size());
  parallelRanges(values.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t e = begin; e < end; ++e)
    {
      out[e] = smoothElement([&values](std::size_t i) { return values[i]; }, e,
        elements.vertexOf(e), topology.neighbourOffsets.data(), topology.neighbours.data(),
        normals.data(), cosFeatureAngle);
    }
  });
  return out;
}
}
