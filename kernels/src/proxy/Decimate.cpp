// The proxy's decimation, with OpenMesh: the only file of the engine that includes it.
#include "linkgi/Proxy.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

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
  /// `collapses` in all, of which `done` before the Decimater.
  ProgressObserver(std::size_t collapses, const ProgressCallback& progress, std::size_t done)
    : Observer(std::max<std::size_t>(1, collapses / 100)), collapses(std::max<std::size_t>(1, collapses)),
      done(done), progress(progress)
  {
  }
  void notify(std::size_t step) override
  {
    if (!aborted && !progress("Decimate", std::min(1.0, double(done + step) / double(collapses))))
    {
      aborted = true;
    }
  }
  bool abort() const override { return aborted; }
  bool aborted = false;

private:
  std::size_t collapses, done;
  const ProgressCallback& progress;
};

Vec3f toVec(const Mesh::Point& p)
{
  return { p[0], p[1], p[2] };
}

/// Twice a triangle's area over its longest edge squared below which it is a sliver (its
/// smallest angle under about 0.1 degree).
constexpr float kSliver = 2e-3f;

/// Whether collapsing `from` into `to` keeps every triangle around `from` (but the two the
/// collapse removes) no sliver, its edges from `to` within `maxEdge2` (squared), and
/// its normal within the angle of `minCos` of the input normal at each of its corners. The
/// rule of both the sweep and the decimater (ModInputNormalsT), so that no decimated
/// triangle faces away from the input normals that the light was solved for.
bool keepsInputNormals(const Mesh& mesh, const Scene& scene, const OpenMesh::VPropHandleT<Index>& source,
  Mesh::VertexHandle from, Mesh::VertexHandle to, float minCos, double maxEdge2)
{
  const Mesh::Point target = mesh.point(to);
  for (auto f = mesh.cvf_iter(from); f.is_valid(); ++f)
  {
    Mesh::Point corner[3];
    Index input[3];
    int k = 0;
    bool touchesTo = false;
    for (const auto v : mesh.fv_range(*f))
    {
      touchesTo |= v == to;
      // After the collapse this corner is `to`: its place and its input normal.
      corner[k] = v == from ? target : mesh.point(v);
      input[k++] = mesh.property(source, v == from ? to : Mesh::VertexHandle(v));
    }
    if (touchesTo)
    {
      continue; // one of the two faces the collapse removes
    }
    const Mesh::Point n = (corner[1] - corner[0]) % (corner[2] - corner[0]);
    const float norm = n.norm();
    const float longest2 = std::max({ (corner[1] - corner[0]).sqrnorm(), (corner[2] - corner[1]).sqrnorm(),
      (corner[0] - corner[2]).sqrnorm() });
    if (!(norm > kSliver * longest2))
    {
      return false; // a sliver: its normal is rounding noise
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!((corner[c] - target).sqrnorm() <= maxEdge2 && dot(toVec(n), scene.normals[input[c]]) >= minCos * norm))
      {
        return false;
      }
    }
  }
  return true;
}

/// The same rule as a binary module of OpenMesh's decimaters.
template <class MeshT>
class ModInputNormalsT : public OpenMesh::Decimater::ModBaseT<MeshT>
{
public:
  DECIMATING_MODULE(ModInputNormalsT, MeshT, InputNormals);
  explicit ModInputNormalsT(MeshT& mesh) : Base(mesh, true) {}
  void setRule(const Scene& input, const OpenMesh::VPropHandleT<Index>& sourceVertex, float minimumCos)
  {
    scene = &input;
    source = sourceVertex;
    minCos = minimumCos;
  }
  float collapse_priority(const CollapseInfo& ci) override
  {
    return keepsInputNormals(Base::mesh(), *scene, source, ci.v0, ci.v1, minCos, std::numeric_limits<double>::max())
      ? float(Base::LEGAL_COLLAPSE)
      : float(Base::ILLEGAL_COLLAPSE);
  }

private:
  const Scene* scene = nullptr;
  OpenMesh::VPropHandleT<Index> source;
  float minCos = 0.f;
};

/// The first, fast part of a large decimation: sweeps over the edges collapsing each one
/// shorter than `length`, the first time with half of it and then longer, until at most
/// `stopAt` vertices are left. A collapse removes an unlocked end and is refused where
/// OpenMesh's topology test refuses it, where it would make an edge longer than `maxEdge`,
/// or where a triangle around the removed vertex would turn away (by more than
/// `minCos`'s angle) from an input normal at one of its corners (keepsInputNormals). It
/// needs no priorities: on a 1M-vertex isosurface a collapse took 2.5-3.6 us against the
/// multiple-choice Decimater's 37-53 us, whose quadric order then takes the last collapses
/// to the target. Throws Aborted when `progress` says so.
void collapseShortEdges(Mesh& mesh, const Scene& scene, const OpenMesh::VPropHandleT<Index>& source,
  double length, double maxEdge, float minCos, std::size_t stopAt, std::size_t collapses,
  const ProgressCallback& progress)
{
  std::size_t left = mesh.n_vertices(), done = 0;
  const double maxEdge2 = maxEdge * maxEdge;
  for (const double scale : { 0.5, 0.7, 0.85, 1.0 })
  {
    const double limit2 = scale * scale * length * length;
    const std::size_t edges = mesh.n_edges();
    for (std::size_t i = 0; i < edges && left > stopAt; ++i)
    {
      const Mesh::EdgeHandle e = mesh.edge_handle(static_cast<unsigned int>(i));
      if (mesh.status(e).deleted())
      {
        continue;
      }
      if ((i & 0xffff) == 0 && progress && !progress("Decimate", std::min(1.0, double(done) / double(collapses))))
      {
        throw Aborted();
      }
      Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      if ((mesh.point(mesh.to_vertex_handle(h)) - mesh.point(mesh.from_vertex_handle(h))).sqrnorm() >= limit2)
      {
        continue;
      }
      for (int side = 0; side < 2; ++side, h = mesh.opposite_halfedge_handle(h))
      {
        const Mesh::VertexHandle from = mesh.from_vertex_handle(h), to = mesh.to_vertex_handle(h);
        if (mesh.status(from).locked() || !mesh.is_collapse_ok(h))
        {
          continue;
        }
        const bool ok = keepsInputNormals(mesh, scene, source, from, to, minCos, maxEdge2);
        if (ok)
        {
          mesh.collapse(h);
          --left;
          ++done;
          break;
        }
      }
    }
  }
}
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

  // The light lives on the vertices: a flat wall (no quadric error) must not become two
  // triangles between its corners, whose light is that of the corners. Edges stay within
  // twice those of an even mesh of the target size (2 triangles per vertex).
  double area = 0.0;
  for (const auto f : mesh.faces())
  {
    area += mesh.calc_face_area(f);
  }
  const auto evenEdge = [area](double vertices) {
    return std::sqrt(4.0 * area / (2.0 * vertices * std::sqrt(3.0)));
  };
  const std::size_t collapses = scene.vertexCount() - targetVertices;
  // A large decimation collapses the short edges first, down to twice the target (edges
  // about those of an even mesh of that size), and leaves the rest to the Decimater.
  const std::size_t sweptTo = 2 * targetVertices;
  const float minCos = float(std::cos(double(maxNormalDeviationDegrees) * 3.14159265358979 / 180.0));
  if (scene.vertexCount() > 2 * sweptTo)
  {
    collapseShortEdges(mesh, scene, source, evenEdge(double(sweptTo)), 2.0 * evenEdge(double(targetVertices)),
      minCos, sweptTo, collapses, progress);
    mesh.garbage_collection();
    mesh.update_face_normals();
  }

  Decimater decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  OpenMesh::Decimater::ModNormalDeviationT<Mesh>::Handle deviation;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
  OpenMesh::Decimater::ModEdgeLengthT<Mesh>::Handle edgeLength;
  ModInputNormalsT<Mesh>::Handle inputNormals;
  decimater.add(quadric);
  decimater.add(deviation);
  decimater.add(flipping);
  decimater.add(edgeLength);
  decimater.add(inputNormals);
  decimater.module(inputNormals).setRule(scene, source, minCos);
  decimater.module(deviation).set_normal_deviation(maxNormalDeviationDegrees);
  decimater.module(edgeLength).set_edge_length(float(2.0 * evenEdge(double(targetVertices))));
  decimater.module(edgeLength).set_binary(true);
  decimater.initialize();
  // OpenMesh logs when it runs out of legal collapses before the target; the caller sees
  // that in the proxy's size instead (ProxySolver warns).
  const bool logging = omlog().is_enabled();
  omlog().disable();
  ProgressObserver observer(collapses, progress, scene.vertexCount() - mesh.n_vertices());
  if (progress)
  {
    decimater.set_observer(&observer);
  }
  // The decimater draws its candidates from the C library's rand(): seeded here, a proxy is
  // the same on every run and on every process of a partitioned surface.
  std::srand(1u);
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
