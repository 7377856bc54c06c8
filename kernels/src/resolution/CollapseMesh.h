// The decimation's OpenMesh mesh, with the halfedge collapse, its topology test and adding a
// triangle compiled here from OpenMesh's inline accessors, with the library's logic. The
// library's own (PolyConnectivity::collapse and add_face, TriConnectivity::is_collapse_ok)
// live in libOpenMeshCore, which Debian builds with its assertions on: there every status
// lookup builds and compares two type-name strings and every handle is checked by an
// out-of-line call, over a third of a 1M-vertex decimation's time. collapse and
// is_collapse_ok keep the library's names, so that OpenMesh's decimaters, templates on the
// mesh type, call these too.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace linkgi
{
struct CollapseMeshTraits : OpenMesh::DefaultTraits
{
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  // With the previous halfedge stored, finding it is a lookup instead of a walk around the
  // face or the boundary loop (which is long while a mesh is being built).
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
};

class CollapseMesh : public OpenMesh::TriMesh_ArrayKernelT<CollapseMeshTraits>
{
public:
  /// Whether collapsing `v0v1` (its from-vertex into its to-vertex) keeps the mesh a
  /// manifold: OpenMesh's rules (neither end nor the edge deleted; not both other edges of
  /// a triangle on the boundary; the one-rings share only the two opposite vertices; an
  /// edge between two boundary vertices is a boundary edge). Uses the vertices' tag bits.
  bool is_collapse_ok(HalfedgeHandle v0v1)
  {
    if (status(edge_handle(v0v1)).deleted())
    {
      return false;
    }
    const HalfedgeHandle v1v0 = opposite_halfedge_handle(v0v1);
    const VertexHandle v0 = to_vertex_handle(v1v0), v1 = to_vertex_handle(v0v1);
    if (status(v0).deleted() || status(v1).deleted())
    {
      return false;
    }
    // The vertex opposite the edge in the triangle left of `h`, if any; invalid when the
    // triangle's two other edges are both boundary edges (a collapse would leave a dangling
    // triangle).
    bool dangling = false;
    const auto opposite = [&](HalfedgeHandle h) {
      if (is_boundary(h))
      {
        return VertexHandle();
      }
      const HalfedgeHandle h1 = next_halfedge_handle(h), h2 = next_halfedge_handle(h1);
      dangling |= is_boundary(opposite_halfedge_handle(h1)) && is_boundary(opposite_halfedge_handle(h2));
      return to_vertex_handle(h1);
    };
    const VertexHandle vl = opposite(v0v1), vr = opposite(v1v0);
    if (dangling || vl == vr)
    {
      return false;
    }
    forOutgoing(v0, [&](HalfedgeHandle h) { status(to_vertex_handle(h)).set_tagged(false); });
    forOutgoing(v1, [&](HalfedgeHandle h) { status(to_vertex_handle(h)).set_tagged(true); });
    bool shared = false;
    forOutgoing(v0, [&](HalfedgeHandle h) {
      const VertexHandle v = to_vertex_handle(h);
      shared |= status(v).tagged() && v != vl && v != vr;
    });
    if (shared)
    {
      return false;
    }
    return !(is_boundary(v0) && is_boundary(v1) && !is_boundary(v0v1) && !is_boundary(v1v0));
  }

  /// Collapses the from-vertex of `h` into its to-vertex, as OpenMesh's collapse does:
  /// the edge goes, and so do the triangles on its sides (now loops of two edges).
  void collapse(HalfedgeHandle h)
  {
    const HalfedgeHandle h1 = next_halfedge_handle(h);
    const HalfedgeHandle o1 = next_halfedge_handle(opposite_halfedge_handle(h));
    collapseEdge(h);
    if (next_halfedge_handle(next_halfedge_handle(h1)) == h1)
    {
      collapseLoop(next_halfedge_handle(h1));
    }
    if (next_halfedge_handle(next_halfedge_handle(o1)) == o1)
    {
      collapseLoop(o1);
    }
  }

  /// Adds triangle abc as OpenMesh's add_face does, with the same refusals (an invalid
  /// handle, nothing changed): a corner that is not on the boundary (complex vertex), an
  /// edge that already has a triangle on this side (complex edge), or a fan that cannot be
  /// re-linked around a corner.
  FaceHandle addTriangle(VertexHandle a, VertexHandle b, VertexHandle c)
  {
    const VertexHandle corner[3] = { a, b, c };
    HalfedgeHandle inner[3]; // corner[i] -> corner[i + 1]
    bool fresh[3], adjust[3] = { false, false, false };
    for (int i = 0; i < 3; ++i)
    {
      if (!is_boundary(corner[i]))
      {
        return FaceHandle();
      }
      inner[i] = findHalfedge(corner[i], corner[(i + 1) % 3]);
      fresh[i] = !inner[i].is_valid();
      if (!fresh[i] && !is_boundary(inner[i]))
      {
        return FaceHandle();
      }
    }
    // The next-links to set, all at the end (at most 3 per corner, as OpenMesh's cache).
    std::pair<HalfedgeHandle, HalfedgeHandle> links[9];
    int linkCount = 0;
    // Two existing edges at a corner that do not follow each other: the fan between them
    // moves into a free gap of the corner's boundary.
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      if (fresh[i] || fresh[j] || next_halfedge_handle(inner[i]) == inner[j])
      {
        continue;
      }
      const HalfedgeHandle outerPrev = opposite_halfedge_handle(inner[j]);
      HalfedgeHandle boundaryPrev = outerPrev;
      do
      {
        boundaryPrev = opposite_halfedge_handle(next_halfedge_handle(boundaryPrev));
      } while (!is_boundary(boundaryPrev));
      if (boundaryPrev == inner[i])
      {
        return FaceHandle();
      }
      const HalfedgeHandle boundaryNext = next_halfedge_handle(boundaryPrev);
      links[linkCount++] = { boundaryPrev, next_halfedge_handle(inner[i]) };
      links[linkCount++] = { prev_halfedge_handle(inner[j]), boundaryNext };
      links[linkCount++] = { inner[i], inner[j] };
    }
    for (int i = 0; i < 3; ++i)
    {
      if (fresh[i])
      {
        inner[i] = new_edge(corner[i], corner[(i + 1) % 3]);
      }
    }
    const FaceHandle face = new_face();
    set_halfedge_handle(face, inner[2]);
    for (int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3;
      const VertexHandle v = corner[j];
      const HalfedgeHandle outerPrev = opposite_halfedge_handle(inner[j]);
      const HalfedgeHandle outerNext = opposite_halfedge_handle(inner[i]);
      if (fresh[i] && !fresh[j])
      {
        links[linkCount++] = { prev_halfedge_handle(inner[j]), outerNext };
        set_halfedge_handle(v, outerNext);
      }
      else if (!fresh[i] && fresh[j])
      {
        const HalfedgeHandle boundaryNext = next_halfedge_handle(inner[i]);
        links[linkCount++] = { outerPrev, boundaryNext };
        set_halfedge_handle(v, boundaryNext);
      }
      else if (fresh[i] && fresh[j])
      {
        if (!halfedge_handle(v).is_valid())
        {
          set_halfedge_handle(v, outerNext);
          links[linkCount++] = { outerPrev, outerNext };
        }
        else
        {
          const HalfedgeHandle boundaryNext = halfedge_handle(v);
          links[linkCount++] = { prev_halfedge_handle(boundaryNext), outerNext };
          links[linkCount++] = { outerPrev, boundaryNext };
        }
      }
      else
      {
        adjust[j] = halfedge_handle(v) == inner[j];
      }
      if (fresh[i] || fresh[j])
      {
        links[linkCount++] = { inner[i], inner[j] };
      }
      set_face_handle(inner[i], face);
    }
    for (int k = 0; k < linkCount; ++k)
    {
      set_next_halfedge_handle(links[k].first, links[k].second);
    }
    for (int i = 0; i < 3; ++i)
    {
      if (adjust[i])
      {
        adjustOutgoing(corner[i]);
      }
    }
    return face;
  }

private:
  /// The first halfedge going out of `v` for which `match` is true, or an invalid one (also
  /// for an isolated vertex). The one loop around a vertex that everything here uses.
  template <class Match>
  HalfedgeHandle findOutgoing(VertexHandle v, Match&& match) const
  {
    const HalfedgeHandle first = halfedge_handle(v);
    if (first.is_valid())
    {
      HalfedgeHandle h = first;
      do
      {
        if (match(h))
        {
          return h;
        }
        h = next_halfedge_handle(opposite_halfedge_handle(h));
      } while (h != first);
    }
    return HalfedgeHandle();
  }

  /// Calls f on each halfedge going out of `v`.
  template <class F>
  void forOutgoing(VertexHandle v, F&& f) const
  {
    findOutgoing(v, [&](HalfedgeHandle h) {
      f(h);
      return false;
    });
  }

  /// The halfedge from `from` to `to`, or an invalid one.
  HalfedgeHandle findHalfedge(VertexHandle from, VertexHandle to) const
  {
    return findOutgoing(from, [&](HalfedgeHandle h) { return to_vertex_handle(h) == to; });
  }

  /// A vertex's outgoing halfedge is a boundary one where it has any, as OpenMesh keeps it.
  void adjustOutgoing(VertexHandle v)
  {
    const HalfedgeHandle boundary = findOutgoing(v, [&](HalfedgeHandle h) { return is_boundary(h); });
    if (boundary.is_valid())
    {
      set_halfedge_handle(v, boundary);
    }
  }

  /// Removes the edge of `h`, moving every halfedge that ended at its from-vertex to its
  /// to-vertex; leaves the two triangles beside it as loops of two halfedges.
  void collapseEdge(HalfedgeHandle h)
  {
    const HalfedgeHandle hn = next_halfedge_handle(h), hp = prev_halfedge_handle(h);
    const HalfedgeHandle o = opposite_halfedge_handle(h);
    const HalfedgeHandle on = next_halfedge_handle(o), op = prev_halfedge_handle(o);
    const FaceHandle fh = face_handle(h), fo = face_handle(o);
    const VertexHandle vh = to_vertex_handle(h), vo = to_vertex_handle(o);
    // Incoming halfedges of vo are the opposites of its outgoing ones.
    forOutgoing(vo, [&](HalfedgeHandle out) { set_vertex_handle(opposite_halfedge_handle(out), vh); });
    set_next_halfedge_handle(hp, hn);
    set_next_halfedge_handle(op, on);
    if (fh.is_valid())
    {
      set_halfedge_handle(fh, hn);
    }
    if (fo.is_valid())
    {
      set_halfedge_handle(fo, on);
    }
    if (halfedge_handle(vh) == o)
    {
      set_halfedge_handle(vh, hn);
    }
    adjustOutgoing(vh);
    set_isolated(vo);
    status(edge_handle(h)).set_deleted(true);
    status(vo).set_deleted(true);
    status(h).set_deleted(true);
    status(o).set_deleted(true);
  }

  /// Removes a loop of two halfedges (`h0` and the next one): its face and h0's edge go,
  /// the other halfedge takes h0's opposite's place.
  void collapseLoop(HalfedgeHandle h0)
  {
    const HalfedgeHandle h1 = next_halfedge_handle(h0);
    const HalfedgeHandle o0 = opposite_halfedge_handle(h0), o1 = opposite_halfedge_handle(h1);
    const VertexHandle v0 = to_vertex_handle(h0), v1 = to_vertex_handle(h1);
    const FaceHandle fh = face_handle(h0), fo = face_handle(o0);
    set_next_halfedge_handle(h1, next_halfedge_handle(o0));
    set_next_halfedge_handle(prev_halfedge_handle(o0), h1);
    set_face_handle(h1, fo);
    set_halfedge_handle(v0, h1);
    adjustOutgoing(v0);
    set_halfedge_handle(v1, o1);
    adjustOutgoing(v1);
    if (fo.is_valid() && halfedge_handle(fo) == o0)
    {
      set_halfedge_handle(fo, h1);
    }
    if (fh.is_valid())
    {
      set_halfedge_handle(fh, InvalidHalfedgeHandle);
      status(fh).set_deleted(true);
    }
    status(edge_handle(h0)).set_deleted(true);
    status(h0).set_deleted(true);
    status(o0).set_deleted(true);
  }
};
}
