// Light exchange over the link structure: Jacobi bounces and feature-aware smoothing.
#pragma once

#include "linkgi/Links.h"

namespace linkgi
{
/// y = M x for RGB vectors (one gather per row; rows in parallel).
void gatherRgb(const SparseMatrix& m, const Vec3f* x, Vec3f* y);

/// Per-element inputs of the bounce iteration.
struct BounceInputs
{
  std::vector<Vec3f> fixedIrradiance; ///< E_d + E_env: irradiance that does not bounce in
  std::vector<Vec3f> albedo;          ///< rho per element
  std::vector<Vec3f> emission;        ///< Le per element (empty = none)
};

/// n_B Jacobi bounces from E_ind = 0: L = Le + rho/pi (E_fixed + E_ind), E_ind = W L.
/// Returns E_ind, which holds light that bounced up to n_B times plus the emission of
/// emissive elements gathered through the links.
std::vector<Vec3f> iterateBounces(const SparseMatrix& transport, const BounceInputs& inputs,
  std::uint32_t bounces, const ProgressCallback& progress = {});

/// Eq. 5-6 of the paper: each element becomes the mean of itself and those one-ring
/// neighbours whose normals are within the feature angle (dot > cosFeatureAngle).
std::vector<Vec3f> smoothFeatureAware(const std::vector<Vec3f>& values, const Topology& topology,
  const std::vector<Vec3f>& normals, const Elements& elements, float cosFeatureAngle);
}
