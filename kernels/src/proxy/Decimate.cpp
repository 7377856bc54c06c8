// The proxy's decimation, with OpenMesh: the only file of the engine that includes it.
#include "linkgi/Proxy.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/McDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModEdgeLengthT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace linkgi
{
namespace
{
struct Traits : OpenMesh::DefaultTraits
{
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;
// Multiple choice (the best of a few random candidates per collapse, no priority queue):
// 3.5x faster than the greedy DecimaterT here (34k -> 4.9k vertices: 1.4 s against 5.2 s of
// CPU on the 2-core VM), for a proxy whose light is what matters, not its exact shape.
using Decimater = OpenMesh::Decimater::McDecimaterT<Mesh>;
}

bool proxyAvailable()
{
  return true;
}

namespace
{
/// Hands OpenMesh's progress to a ProgressCallback, and its abort back to the decimater.
class ProgressObserver final : public OpenMesh::Decimater::Observer
{
public:
  ProgressObserver(std::size_t collapses, const ProgressCallback& progress)
    : Observer(std::max<std::size_t>(1, collapses / 100)), collapses(std::max<std::size_t>(1, collapses)),
      progress(progress)
  {
  }
  void notify(std::size_t step) override
  {
    if (!aborted && !progress("Decimate", std::min(1.0, double(step) / double(collapses))))
    {
      aborted = true;
    }
  }
  bool abort() const override { return aborted; }
  bool aborted = false;

private:
  std::size_t collapses;
  const ProgressCallback& progress;
};
}

ProxyMesh decimate(const Scene& scene, std::size_t targetVertices, float maxNormalDeviationDegrees,
  const ProgressCallback& progress)
{
  if (targetVertices == 0 || targetVertices >= scene.vertexCount())
  {
    throw Error("The proxy must have fewer vertices than the input (" + std::to_string(scene.vertexCount()) +
      ") and at least 1; got " + std::to_string(targetVertices) + ". Use 0 for no proxy.");
  }
  Mesh mesh;
  OpenMesh::VPropHandleT<Index> source; // survives garbage collection's renumbering
  mesh.add_property(source);
  std::vector<Mesh::VertexHandle> handles(scene.vertexCount());
  for (std::size_t v = 0; v < handles.size(); ++v)
  {
    const Vec3f& p = scene.positions[v];
    handles[v] = mesh.add_vertex(Mesh::Point(p.x, p.y, p.z));
    mesh.property(source, handles[v]) = Index(v);
  }
  ProxyMesh out;
  for (const Triangle& t : scene.triangles)
  {
    // OpenMesh refuses faces that would make an edge non-manifold (returns an invalid handle).
    if (!mesh.add_face(handles[t.v[0]], handles[t.v[1]], handles[t.v[2]]).is_valid())
    {
      ++out.droppedTriangles;
    }
  }
  mesh.update_face_normals();
  // Boundary vertices stay: open borders and the seams of split normals keep their shape.
  for (const auto v : mesh.vertices())
  {
    mesh.status(v).set_locked(mesh.is_boundary(v));
  }

  Decimater decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalDeviationT<Mesh>::Handle deviation;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
  OpenMesh::Decimater::ModEdgeLengthT<Mesh>::Handle edgeLength;
  decimater.add(quadric);
  decimater.add(deviation);
  decimater.add(flipping);
  decimater.add(edgeLength);
  decimater.module(deviation).set_normal_deviation(maxNormalDeviationDegrees);
  // The light lives on the vertices: a flat wall (no quadric error) must not become two
  // triangles between its corners, whose light is that of the corners. Edges stay within
  // twice those of an even mesh of the target size (2 triangles per vertex).
  double area = 0.0;
  for (const auto f : mesh.faces())
  {
    area += mesh.calc_face_area(f);
  }
  const double evenEdge = std::sqrt(4.0 * area / (2.0 * double(targetVertices) * std::sqrt(3.0)));
  decimater.module(edgeLength).set_edge_length(float(2.0 * evenEdge));
  decimater.module(edgeLength).set_binary(true);
  decimater.initialize();
  // OpenMesh logs when it runs out of legal collapses before the target; the caller sees
  // that in the proxy's size instead (ProxySolver warns).
  const bool logging = omlog().is_enabled();
  omlog().disable();
  ProgressObserver observer(scene.vertexCount() - targetVertices, progress);
  if (progress)
  {
    decimater.set_observer(&observer);
  }
  decimater.decimate_to(targetVertices);
  if (logging)
  {
    omlog().enable();
  }
  if (observer.aborted)
  {
    throw Aborted();
  }
  mesh.garbage_collection();

  // The proxy: the kept vertices that still have faces, with the input's data for each.
  Scene& p = out.scene;
  std::vector<Index> proxyIndex(mesh.n_vertices(), kInvalidIndex);
  for (const auto v : mesh.vertices())
  {
    if (mesh.is_isolated(v))
    {
      continue;
    }
    const Index from = mesh.property(source, v);
    proxyIndex[v.idx()] = Index(out.sourceVertex.size());
    out.sourceVertex.push_back(from);
    p.positions.push_back(scene.positions[from]);
    p.normals.push_back(scene.normals[from]);
    p.albedo.push_back(scene.albedo[from]);
    if (!scene.emission.empty())
    {
      p.emission.push_back(scene.emission[from]);
    }
  }
  for (const auto f : mesh.faces())
  {
    Triangle t;
    int k = 0;
    for (const auto v : mesh.fv_range(f))
    {
      t.v[k++] = proxyIndex[v.idx()];
    }
    p.triangles.push_back(t);
  }
  p.lights = scene.lights;
  p.environment = scene.environment;
  p.lengthExponent = scene.lengthExponent;
  return out;
}
}
