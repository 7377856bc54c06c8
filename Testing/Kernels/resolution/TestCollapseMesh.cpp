// The decimation's own construction, halfedge collapse and topology test
// (resolution/CollapseMesh.h) against OpenMesh's: the same triangles refused, the same
// answer for every edge asked, and the same connectivity, down to every handle and deleted
// flag, after every triangle and every collapse.
#include "SceneFixtures.h"

#include "linkgi/Scenes.h"
#include "resolution/CollapseMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace linkgi;

namespace
{
std::string difference(const CollapseMesh& a, const CollapseMesh& b);

/// `ours` and `theirs` built from the same triangles, with CollapseMesh::addTriangle and
/// with OpenMesh's add_face; checks that they agree after every triangle.
void buildBoth(CollapseMesh& ours, CollapseMesh& theirs, const Scene& s)
{
  for (const Vec3f& p : s.positions)
  {
    ours.add_vertex(CollapseMesh::Point(p.x, p.y, p.z));
    theirs.add_vertex(CollapseMesh::Point(p.x, p.y, p.z));
  }
  const bool logging = omerr().is_enabled(); // OpenMesh logs each triangle it refuses
  omerr().disable();
  for (std::size_t k = 0; k < s.triangles.size(); ++k)
  {
    const Triangle& t = s.triangles[k];
    const auto a = ours.vertex_handle(t.v[0]), b = ours.vertex_handle(t.v[1]), c = ours.vertex_handle(t.v[2]);
    const auto mine = ours.addTriangle(a, b, c);
    const auto reference = theirs.OpenMesh::TriConnectivity::add_face(a, b, c);
    ASSERT_EQ(mine, reference) << "triangle " << k;
    ASSERT_EQ(difference(ours, theirs), "") << "after triangle " << k;
  }
  if (logging)
  {
    omerr().enable();
  }
}

/// Triangles OpenMesh takes only by re-linking a fan, and ones it refuses: a vertex where
/// two fans meet, then the triangle that joins them (relinked), triangles on an edge that
/// has one on each side or on that side already (complex edge), one at a vertex closed all
/// round (complex vertex), and a repeat.
Scene awkwardTriangles()
{
  Scene s;
  for (int i = 0; i < 12; ++i)
  {
    const float a = 0.5236f * float(i);
    s.positions.push_back({ std::cos(a), std::sin(a), 0.f });
  }
  s.positions.push_back({ 0.f, 0.f, 0.f });  // 12: the centre
  s.positions.push_back({ 0.f, 0.f, 1.f });  // 13: above it
  s.positions.push_back({ 3.f, 3.f, 0.f });  // 14: far away
  const Index c = 12;
  s.triangles = {
    { { c, 0, 1 } }, { { c, 1, 2 } },   // one fan
    { { c, 6, 7 } }, { { c, 7, 8 } },   // another fan at the same centre
    { { c, 3, 4 } },                    // a third, alone
    { { c, 2, 3 } },                    // joins the first and the third
    { { c, 8, 9 } }, { { c, 9, 10 } }, { { c, 10, 11 } }, { { c, 11, 0 } }, { { c, 4, 5 } },
    { { c, 5, 6 } },                    // closes the disc around the centre
    { { c, 0, 13 } },                   // an edge with triangles on both sides
    { { c, 13, 14 } },                  // the centre is no longer on the boundary
    { { 1, 0, 13 } },                   // a third triangle on edge 0-1 ...
    { { 0, 1, 14 } },                   // ... and one on its free side
    { { 0, 1, 14 } },                   // the same again
  };
  return s;
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

TEST(TestCollapseMesh, BuildsAndCollapsesAsOpenMeshDoes)
{
  // A closed surface, and open ones whose boundaries take the boundary rules.
  for (const Scene& s :
    { makeStandardScene("torso"), test::roomWithBlock(0.25f), test::twoSquares(true, 12), awkwardTriangles() })
  {
    CollapseMesh ours, theirs;
    buildBoth(ours, theirs, s);
    if (HasFatalFailure())
    {
      return;
    }
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
