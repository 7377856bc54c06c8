// Decimated proxies: the indirect light solved on a coarser copy of the mesh and
// carried back to every input vertex, so a mesh too fine for the memory or the time is lit
// at a resolution the user chooses. The proxy's vertices are input vertices (OpenMesh's
// Decimater collapses halfedges onto existing vertices), so their normals, albedo and
// emission are the input's.
#pragma once

#include "linkgi/Scene.h"
#include "linkgi/SolverTypes.h"

#include <array>
#include <string>
#include <vector>

namespace linkgi
{
/// True if this build has OpenMesh (without it, decimate() throws Error saying so).
bool proxyAvailable();

/// A decimated copy of a scene.
struct ProxyMesh
{
  Scene scene; ///< positions, normals, albedo, emission of the kept vertices; lights, environment
  std::vector<Index> sourceVertex; ///< for each proxy vertex, the input vertex it is
  std::size_t droppedTriangles = 0; ///< input triangles OpenMesh could not take (non-manifold)
};

/// Decimates `scene` (validated) to about `targetVertices` vertices with OpenMesh's Decimater:
/// quadric error as the priority, collapses that turn a face normal by more than
/// `maxNormalDeviationDegrees` or flip it refused, as are those that leave a triangle turned
/// by more than that from the input normal at one of its corners, or a sliver; boundary
/// vertices kept (so the borders of open surfaces and the creases a mesh builder splits stay
/// where they are). Below 40% of the input, a sweep over the mesh's short edges (the same
/// rules, no priorities) first takes it to 1.25 times the target, in two halves of the
/// surface on two threads; an even proxy carries the light better than the quadric's. The same input gives the same proxy on every run and machine.
/// Throws Error for a target of 0 or not smaller than the input, or where this build has no
/// OpenMesh.
/// `progress` hears ("Decimate", fraction of the collapses done) about a hundred times; when
/// it returns false the decimation stops and Aborted is thrown.
ProxyMesh decimate(const Scene& scene, std::size_t targetVertices, float maxNormalDeviationDegrees = 60.f,
  const ProgressCallback& progress = {});

/// Where each input vertex lies on the proxy: its nearest proxy triangle among those facing
/// the same way (normals within 90 degrees; the nearest of all where none does), and the
/// barycentric weights of the closest point on it.
struct ProxyTransfer
{
  std::vector<Triangle> corners;              ///< per input vertex: three proxy vertices
  std::vector<std::array<float, 3>> weights;  ///< per input vertex: their weights (sum 1)
  /// Interpolates per-proxy-vertex `values` onto the input vertices.
  std::vector<Vec3f> apply(const std::vector<Vec3f>& values) const;
};
ProxyTransfer buildTransfer(const Scene& input, const Scene& proxy);
}

#include "linkgi/Solver.h"

#include <memory>

namespace linkgi
{
/// Lighting through a proxy: the indirect light is solved on a decimated copy of the mesh
/// (any method, any backend, under the memory budget: an ordinary Solver) and carried to
/// every input vertex; the direct light of the point, spot and directional lights is
/// computed on the input itself (shadow rays per input vertex, the light-link code of the
/// CPU). The proxy, its transfer and the input's shadow-ray structures are kept while the
/// input's geometry and the target stay the same: a light move does not decimate again.
class ProxySolver
{
public:
  ProxySolver();
  ~ProxySolver();
  ProxySolver(const ProxySolver&) = delete;
  ProxySolver& operator=(const ProxySolver&) = delete;

  /// Solves `scene` with a proxy of about `proxyVertices` vertices (Error when that is 0 or
  /// not smaller than the input). Same errors and guarantees as Solver::update: after an
  /// error or abort, solution() is the previous result.
  const Solution& update(const Scene& scene, const SolverOptions& options, std::size_t proxyVertices,
    const ProgressCallback& progress = {});
  const Solution& solution() const;
  /// The proxy solve's statistics (its elements are the proxy's), plus "Decimate",
  /// "Transfer" and "InputDirect" parts when they ran.
  const SolverStats& stats() const;
  /// The current proxy, and how many times one was made.
  const ProxyMesh& proxy() const;
  std::uint64_t decimations() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
}
