// Light exchange over the link structure: Jacobi bounces and feature-aware smoothing.
#pragma once

#include "cpu/Parallel.h"
#include "scene/Topology.h"
#include "shared/Csr.h"
#include "shared/Surface.h"

#include <functional>

namespace linkgi
{
/// Outgoing radiance of a diffuse element: L = Le + rho/pi (E_fixed + E_ind).
LINKGI_HOST_DEVICE inline Vec3f outgoingRadiance(const Vec3f& albedo, const Vec3f& fixedIrradiance,
  const Vec3f& indirect, const Vec3f& emission)
{
  return albedo * (fixedIrradiance + indirect) * (1.f / kPi) + emission;
}

/// Eq. 5-6 for element e (vertex v = e mod vertexCount): the mean of its value and those of
/// one-ring neighbours whose normals are within the feature angle. `value(i)` reads element
/// i; the back side of a two-sided pair averages with back sides.
template <typename ValueAt>
LINKGI_HOST_DEVICE inline Vec3f smoothElement(const ValueAt& value, std::size_t e, Index v,
  const Index* offsets, const Index* neighbours, const Vec3f* normals, float cosFeatureAngle)
{
  const std::size_t sideOffset = e - v; // 0 for fronts, vertexCount for backs
  Vec3f sum = value(e);
  float count = 1.f;
  for (Index i = offsets[v]; i < offsets[v + 1]; ++i)
  {
    const Index u = neighbours[i];
    // Both sides of a two-sided pair negate both normals, so the test is the same.
    if (dot(normals[v], normals[u]) > cosFeatureAngle)
    {
      sum += value(u + sideOffset);
      count += 1.f;
    }
  }
  return sum / count;
}

/// y = M x for RGB vectors (one gather per row; rows in parallel).
void gatherRgb(const SparseMatrix& m, const Vec3f* x, Vec3f* y);
/// The same over a view: rows whose entry offsets may start anywhere (firstEntry).
void gatherRgb(const CsrRows& m, const Vec3f* x, Vec3f* y);

/// Per-element inputs of the bounce iteration.
struct BounceInputs
{
  std::vector<Vec3f> fixedIrradiance; ///< E_d + E_env: irradiance that does not bounce in
  std::vector<Vec3f> albedo;          ///< rho per element
  std::vector<Vec3f> emission;        ///< Le per element (empty = none)
  /// Columns the transport gathers beyond the elements (the links' detail nodes), after
  /// them in the radiance vector; `extraRadiance(radiance)` writes theirs once the
  /// elements' radiance of a bounce is in place.
  std::size_t extraColumns = 0;
  std::function<void(Vec3f* radiance)> extraRadiance;
};

/// n_B Jacobi bounces from E_ind = 0: L = Le + rho/pi (E_fixed + E_ind), E_ind = W L.
/// Returns E_ind, which holds light that bounced up to n_B times plus the emission of
/// emissive elements gathered through the links.
/// `exchange` (Partition::exchange), when given, completes E_ind after each gather.
std::vector<Vec3f> iterateBounces(const SparseMatrix& transport, const BounceInputs& inputs,
  std::uint32_t bounces, const ProgressCallback& progress = {},
  const std::function<void(std::vector<Vec3f>&)>& exchange = {});

/// Eq. 5-6 of the paper: each element becomes the mean of itself and those one-ring
/// neighbours whose normals are within the feature angle (dot > cosFeatureAngle).
std::vector<Vec3f> smoothFeatureAware(const std::vector<Vec3f>& values, const Topology& topology,
  const std::vector<Vec3f>& normals, const Elements& elements, float cosFeatureAngle);
}
