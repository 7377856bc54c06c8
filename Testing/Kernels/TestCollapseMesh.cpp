// The decimation's own halfedge collapse and topology test (proxy/CollapseMesh.h, issue 15)
// against OpenMesh's: the same answer for every edge asked, and the same connectivity, down
// to every handle and deleted flag, after every collapse.
#include "SceneFixtures.h"

#include "linkgi/Scenes.h"
#include "proxy/CollapseMesh.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

using namespace linkgi;

namespace
{
void build(CollapseMesh& mesh, const Scene& s)
{
  for (const Vec3f& p : s.positions)
  {
    mesh.add_vertex(CollapseMesh::Point(p.x, p.y, p.z));
  }
  for (const Triangle& t : s.triangles)
  {
    mesh.add_face(mesh.vertex_handle(t.v[0]), mesh.vertex_handle(t.v[1]), mesh.vertex_handle(t.v[2]));
  }
}

/// The first difference between the two meshes' connectivity and deleted flags, or "".
std::string difference(const CollapseMesh& a, const CollapseMesh& b)
{
  if (a.n_halfedges() != b.n_halfedges() || a.n_vertices() != b.n_vertices() || a.n_faces() != b.n_faces())
  {
    return "element counts";
  }
  for (unsigned i = 0; i < a.n_halfedges(); ++i)
  {
    const auto h = a.halfedge_handle(i);
    if (a.next_halfedge_handle(h) != b.next_halfedge_handle(h) || a.to_vertex_handle(h) != b.to_vertex_handle(h) ||
      a.face_handle(h) != b.face_handle(h) || a.status(h).deleted() != b.status(h).deleted() ||
      a.status(a.edge_handle(h)).deleted() != b.status(b.edge_handle(h)).deleted())
    {
      return "halfedge " + std::to_string(i);
    }
  }
  for (unsigned i = 0; i < a.n_vertices(); ++i)
  {
    const auto v = a.vertex_handle(i);
    if (a.halfedge_handle(v) != b.halfedge_handle(v) || a.status(v).deleted() != b.status(v).deleted())
    {
      return "vertex " + std::to_string(i);
    }
  }
  for (unsigned i = 0; i < a.n_faces(); ++i)
  {
    const auto f = a.face_handle(i);
    if (a.halfedge_handle(f) != b.halfedge_handle(f) || a.status(f).deleted() != b.status(f).deleted())
    {
      return "face " + std::to_string(i);
    }
  }
  return "";
}
}

TEST(TestCollapseMesh, CollapsesAsOpenMeshDoes)
{
  // A closed surface, and open ones whose boundaries take the boundary rules.
  for (const Scene& s : { makeStandardScene("torso"), test::roomWithBlock(0.25f), test::twoSquares(true, 12) })
  {
    CollapseMesh ours, theirs;
    build(ours, s);
    build(theirs, s);
    ASSERT_EQ(difference(ours, theirs), "");
    std::mt19937 random(7);
    std::size_t collapsed = 0, refused = 0;
    // Random edges until three quarters of the vertices are gone: late collapses meet high
    // valences, boundaries reached from inside, and edges already deleted.
    while (collapsed < 3 * s.vertexCount() / 4 && refused < 100 * s.vertexCount())
    {
      const auto h = ours.halfedge_handle(unsigned(random() % ours.n_halfedges()));
      const bool ok = ours.is_collapse_ok(h);
      ASSERT_EQ(ok, theirs.OpenMesh::TriConnectivity::is_collapse_ok(h)) << "halfedge " << h.idx();
      if (!ok)
      {
        ++refused;
        continue;
      }
      ours.collapse(h);
      theirs.OpenMesh::PolyConnectivity::collapse(h);
      ++collapsed;
      ASSERT_EQ(difference(ours, theirs), "") << "after collapsing halfedge " << h.idx();
    }
    EXPECT_GE(collapsed, 3 * s.vertexCount() / 4);
    EXPECT_GT(refused, 0u);
  }
}
