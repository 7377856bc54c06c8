// The proxy's decimation, with OpenMesh: the only file of the engine that includes it (with
// proxy/CollapseMesh.h, its mesh).
#include "resolution/Decimate.h"

#include "linkgi/Error.h"
#include "resolution/CollapseMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <atomic>
#include <functional>
#include <future>
#include <limits>
#include <numeric>

#include <OpenMesh/Tools/Decimater/McDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModEdgeLengthT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

namespace linkgi
{
namespace
{
using Mesh = CollapseMesh;
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
/// `stopAt` vertices are left. A collapse removes an unlocked end, never into a vertex that
/// `seam` marks (by input vertex; empty: none), and is refused where OpenMesh's topology
/// test refuses it, where it would make an edge longer than `maxEdge`, or where a triangle
/// around the removed vertex would turn away (by more than `minCos`'s angle) from an input
/// normal at one of its corners (keepsInputNormals). It needs no priorities: on a 1M-vertex
/// isosurface a collapse takes 0.5-0.7 us against the multiple-choice Decimater's 20-40 us,
/// whose quadric order then takes the last collapses to the target. `done` counts the
/// collapses of every sweep that runs at the same time; `keepGoing` is asked now and then
/// (with the fraction of `collapses` done) and ends the sweep with Aborted when it says no.
void collapseShortEdges(Mesh& mesh, const Scene& scene, const OpenMesh::VPropHandleT<Index>& source,
  const std::vector<std::uint8_t>& seam, double length, double maxEdge, float minCos, std::size_t stopAt,
  std::size_t collapses, std::atomic<std::size_t>& done, const std::function<bool(double)>& keepGoing)
{
  std::size_t left = mesh.n_vertices(), mine = 0;
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
      if ((i & 0xffff) == 0)
      {
        done += mine; // the shared count, not touched per collapse
        mine = 0;
        if (!keepGoing(std::min(1.0, double(done.load()) / double(collapses))))
        {
          throw Aborted();
        }
      }
      Mesh::HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      if ((mesh.point(mesh.to_vertex_handle(h)) - mesh.point(mesh.from_vertex_handle(h))).sqrnorm() >= limit2)
      {
        continue;
      }
      for (int side = 0; side < 2; ++side, h = mesh.opposite_halfedge_handle(h))
      {
        const Mesh::VertexHandle from = mesh.from_vertex_handle(h), to = mesh.to_vertex_handle(h);
        if (mesh.status(from).locked() || (!seam.empty() && seam[mesh.property(source, to)]) ||
          !mesh.is_collapse_ok(h))
        {
          continue;
        }
        if (keepsInputNormals(mesh, scene, source, from, to, minCos, maxEdge2))
        {
          mesh.collapse(h);
          --left;
          ++mine;
          break;
        }
      }
    }
  }
}

/// The OpenMesh mesh of `triangles` (of the input's vertices), each vertex with its input
/// index in `source`, boundary vertices locked. Returns how many triangles OpenMesh refused
/// (they would make an edge non-manifold).
std::size_t buildMesh(Mesh& mesh, const OpenMesh::VPropHandleT<Index>& source, const Scene& scene,
  const std::vector<Triangle>& triangles)
{
  std::vector<Mesh::VertexHandle> handles(scene.vertexCount());
  // Reserved, OpenMesh's arrays are not regrown while the faces go in: a closed surface has a
  // vertex per two triangles and three edges per two.
  mesh.reserve(triangles.size() / 2 + 16, 3 * triangles.size() / 2 + 16, triangles.size());
  for (const Triangle& t : triangles)
  {
    for (const Index v : t.v)
    {
      if (!handles[v].is_valid())
      {
        const Vec3f& p = scene.positions[v];
        handles[v] = mesh.add_vertex(Mesh::Point(p.x, p.y, p.z));
        mesh.property(source, handles[v]) = v;
      }
    }
  }
  std::size_t dropped = 0;
  for (const Triangle& t : triangles)
  {
    if (!mesh.addTriangle(handles[t.v[0]], handles[t.v[1]], handles[t.v[2]]).is_valid())
    {
      ++dropped;
    }
  }
  // Boundary vertices stay: open borders and the seams of split normals keep their shape.
  for (const auto v : mesh.vertices())
  {
    mesh.status(v).set_locked(mesh.is_boundary(v));
  }
  return dropped;
}

/// The triangles of `mesh` (not deleted) as input vertex indices.
std::vector<Triangle> trianglesOf(const Mesh& mesh, const OpenMesh::VPropHandleT<Index>& source)
{
  std::vector<Triangle> out;
  out.reserve(mesh.n_faces());
  for (const auto f : mesh.faces())
  {
    Triangle t;
    int k = 0;
    for (const auto v : mesh.fv_range(f))
    {
      t.v[k++] = mesh.property(source, v);
    }
    out.push_back(t);
  }
  return out;
}

/// The sweep of a large decimation, in two halves at once: the triangles are cut in two by
/// their centroids at the median along the longest axis, each half is built and swept on a
/// thread of its own (OpenMesh's meshes are sequential), the vertices on the cut stay (a
/// half's boundary is locked) and take no collapse, so the halves' new edges never meet,
/// and the swept halves are joined, with `stopAt` vertices plus those of the cut. The cut
/// is the same on any machine, so is the proxy.
/// Returns the triangles of the swept surface (input vertex indices) and adds the triangles
/// OpenMesh refused to `dropped`.
std::vector<Triangle> sweepInHalves(const Scene& scene, double length, double maxEdge, float minCos,
  std::size_t stopAt, std::size_t collapses, std::atomic<std::size_t>& done, const ProgressCallback& progress,
  std::size_t& dropped)
{
  const std::size_t nt = scene.triangleCount();
  Vec3f lo, hi;
  positionBounds(scene.positions, lo, hi);
  const Vec3f extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  std::vector<float> key(nt);
  for (Index t = 0; t < nt; ++t)
  {
    const Triangle& tri = scene.triangles[t];
    key[t] = (scene.positions[tri.v[0]] + scene.positions[tri.v[1]] + scene.positions[tri.v[2]])[axis];
  }
  // The median triangle along the axis (ties broken by index: the cut does not depend on
  // the library's nth_element); the halves keep the input's order, whose locality OpenMesh's
  // construction and the sweep need.
  std::vector<Index> order(nt);
  std::iota(order.begin(), order.end(), Index(0));
  const auto before = [&](Index a, Index b) {
    const float ka = key[a], kb = key[b];
    return ka < kb || (ka == kb && a < b);
  };
  std::nth_element(order.begin(), order.begin() + nt / 2, order.end(), before);
  const Index median = order[nt / 2];
  std::vector<Index>().swap(order);
  std::vector<Triangle> half[2];
  // Per input vertex: the halves it is in (bits), then whether it is on the cut (in both).
  std::vector<std::uint8_t> seam(scene.vertexCount(), 0);
  for (Index t = 0; t < nt; ++t)
  {
    const int h = before(t, median) ? 0 : 1;
    half[h].push_back(scene.triangles[t]);
    for (const Index v : scene.triangles[t].v)
    {
      seam[v] |= std::uint8_t(1 << h);
    }
  }
  std::size_t onCut = 0;
  for (std::uint8_t& v : seam)
  {
    v = v == 3;
    onCut += v;
  }
  std::atomic<bool> stop{ false };
  std::size_t refused[2] = { 0, 0 };
  const auto sweep = [&](int h, const std::function<bool(double)>& keepGoing) {
    Mesh mesh;
    OpenMesh::VPropHandleT<Index> source;
    mesh.add_property(source);
    refused[h] = buildMesh(mesh, source, scene, half[h]);
    // Each half stops at its share of the vertices to keep, plus the cut's, which it keeps
    // (on a tiny closed surface every vertex can be on the cut: then there is none to take).
    const std::size_t inside = scene.vertexCount() - onCut;
    const std::size_t share =
      onCut + (inside == 0 ? 0 : std::max<std::size_t>(1, stopAt * (mesh.n_vertices() - onCut) / inside));
    collapseShortEdges(mesh, scene, source, seam, length, maxEdge, minCos, share, collapses, done, keepGoing);
    half[h] = trianglesOf(mesh, source); // the faces left, no garbage collection needed
  };
  // This thread reports the progress of both and tells the other one to stop.
  std::future<void> other = std::async(std::launch::async, [&] { sweep(1, [&stop](double) { return !stop; }); });
  try
  {
    sweep(0, [&](double f) { return !progress || progress("Decimate", f); });
  }
  catch (...)
  {
    stop = true;
    throw; // the future waits for the other half
  }
  other.get();
  dropped += refused[0] + refused[1];
  half[0].insert(half[0].end(), half[1].begin(), half[1].end());
  return std::move(half[0]);
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
  // The light lives on the vertices: a flat wall (no quadric error) must not become two
  // triangles between its corners, whose light is that of the corners. Edges stay within
  // twice those of an even mesh of the target size (2 triangles per vertex).
  double area = 0.0;
  for (const Triangle& t : scene.triangles)
  {
    const Vec3f& a = scene.positions[t.v[0]];
    area += 0.5 * double(length(cross(scene.positions[t.v[1]] - a, scene.positions[t.v[2]] - a)));
  }
  const auto evenEdge = [area](double vertices) {
    return std::sqrt(4.0 * area / (2.0 * vertices * std::sqrt(3.0)));
  };
  const std::size_t collapses = scene.vertexCount() - targetVertices;
  // A large decimation collapses the short edges first, down to 1.25 times the target (edges
  // about those of an even mesh of that size), and leaves the rest to the Decimater. An even
  // proxy carries the light better than the quadric's: the 1M-vertex isosurface's carried
  // light is 1.6% off the full solve's this way, 2.3% when the sweep stopped at twice the
  // target (the 200k one's 3.7% and 4.5%).
  const std::size_t sweptTo = targetVertices + targetVertices / 4;
  const float minCos = float(std::cos(double(maxNormalDeviationDegrees) * 3.14159265358979 / 180.0));
  ProxyMesh out;
  Mesh mesh;
  OpenMesh::VPropHandleT<Index> source; // survives garbage collection's renumbering
  mesh.add_property(source);
  if (scene.vertexCount() > 2 * sweptTo)
  {
    const double length = evenEdge(double(sweptTo)), maxEdge = 2.0 * evenEdge(double(targetVertices));
    std::atomic<std::size_t> done{ 0 };
    const std::vector<Triangle> swept =
      sweepInHalves(scene, length, maxEdge, minCos, sweptTo, collapses, done, progress, out.droppedTriangles);
    out.droppedTriangles += buildMesh(mesh, source, scene, swept);
    // The cut, still at the input's resolution, has the shortest edges left.
    collapseShortEdges(mesh, scene, source, {}, length, maxEdge, minCos, sweptTo, collapses, done,
      [&](double f) { return !progress || progress("Decimate", f); });
    mesh.garbage_collection();
  }
  else
  {
    out.droppedTriangles += buildMesh(mesh, source, scene, scene.triangles);
  }

  // The sweeps need none; the Decimater's modules start from them.
  mesh.update_face_normals();
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
  std::vector<Index> proxyIndex(scene.vertexCount(), kInvalidIndex); // by input vertex
  for (const auto v : mesh.vertices())
  {
    if (mesh.is_isolated(v))
    {
      continue;
    }
    const Index from = mesh.property(source, v);
    proxyIndex[from] = Index(out.sourceVertex.size());
    out.sourceVertex.push_back(from);
    p.positions.push_back(scene.positions[from]);
    p.normals.push_back(scene.normals[from]);
    p.albedo.push_back(scene.albedo[from]);
    if (!scene.emission.empty())
    {
      p.emission.push_back(scene.emission[from]);
    }
  }
  for (Triangle t : trianglesOf(mesh, source))
  {
    for (Index& v : t.v)
    {
      v = proxyIndex[v];
    }
    p.triangles.push_back(t);
  }
  p.lights = scene.lights;
  p.environment = scene.environment;
  p.lengthExponent = scene.lengthExponent;
  return out;
}
}
