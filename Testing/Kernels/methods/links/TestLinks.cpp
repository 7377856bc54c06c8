#include "SceneFixtures.h"

#include "methods/links/Links.h"
#include "shared/Metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

using namespace linkgi;

namespace
{
LinkStructure linksOf(const Scene& s, std::uint32_t rays, bool twoSided = false)
{
  auto tracer = createCpuRayTracer(); // Embree, or our BVH where a build has no Embree
  tracer->build(s.positions, s.triangles);
  const LinkOptions o{ rays, twoSided, true, 0 };
  const Topology topo = Topology::build(s.vertexCount(), s.triangles);
  const LinkHits hits = traceLinkRays(s, rayOrigins(s, topo), *tracer, o);
  return compressLinks(s, hits, frontFaceNormals(s), o);
}

float rowSum(const SparseMatrix& m, std::size_t r)
{
  float sum = 0.f;
  for (Index i = m.rowOffsets[r]; i < m.rowOffsets[r + 1]; ++i)
  {
    sum += m.weights[i];
  }
  return sum;
}
}

TEST(TestLinks, EveryRayCarriesPiOverN)
{
  // In an open scene each ray ends either on a front face (W) or in the sky (Wenv), so
  // W + Wenv rows sum to pi, the irradiance of a unit-radiance hemisphere.
  const Scene s = test::twoSquares(false, 8);
  const LinkStructure l = linksOf(s, 64);
  ASSERT_EQ(l.transport.rows(), s.vertexCount());
  EXPECT_EQ(l.rays, s.vertexCount() * 64);
  for (std::size_t r = 0; r < s.vertexCount(); ++r)
  {
    EXPECT_NEAR(rowSum(l.transport, r) + rowSum(l.environment, r), kPi, 1e-4f) << r;
  }
  EXPECT_GE(l.rawLinks, l.transport.nonZeros() + l.environment.nonZeros());
}

TEST(TestLinks, RowsAreMerged)
{
  const Scene s = test::roomWithBlock();
  const LinkStructure l = linksOf(s, 256);
  for (std::size_t r = 0; r < l.transport.rows(); ++r)
  {
    std::vector<Index> cols(l.transport.columns.begin() + l.transport.rowOffsets[r],
      l.transport.columns.begin() + l.transport.rowOffsets[r + 1]);
    std::sort(cols.begin(), cols.end());
    ASSERT_TRUE(std::adjacent_find(cols.begin(), cols.end()) == cols.end()) << "row " << r;
  }
  // Merging must remove links (the ratio itself depends on tessellation vs ray density and
  // is reported by linkgi-bench) and keep every row's total weight.
  EXPECT_LT(l.transport.nonZeros() + l.environment.nonZeros(), l.rawLinks);
}

TEST(TestLinks, TransportIsReciprocal)
{
  // Reciprocity of form factors: A_x F_xy = A_y F_yx, so the area-weighted link mass from
  // square A to square B equals that from B to A (up to sampling noise).
  const Scene s = test::twoSquares(true, 16);
  const LinkStructure l = linksOf(s, 256);
  const std::vector<float> area = vertexAreas(s);
  const std::size_t half = s.vertexCount() / 2;
  double ab = 0, ba = 0;
  for (std::size_t r = 0; r < s.vertexCount(); ++r)
  {
    for (Index i = l.transport.rowOffsets[r]; i < l.transport.rowOffsets[r + 1]; ++i)
    {
      const bool rowInA = r < half, colInA = l.transport.columns[i] < half;
      if (rowInA != colInA)
      {
        (rowInA ? ab : ba) += area[r] * l.transport.weights[i];
      }
    }
  }
  EXPECT_NEAR(ab / ba, 1.0, 0.02);
  EXPECT_NEAR(ab / kPi, 0.2, 0.004); // sum of A_x F_xy = A F = 0.2
}

TEST(TestLinks, BackFacesBlockOrLinkToBackSides)
{
  // Receiver square turned away from the emitter: one-sided it sees black backs (rows sum
  // below pi); two-sided, those hits link to the back-side elements instead.
  MeshBuilder b;
  b.addQuadGrid({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, 4, Vec3f(0.5f)); // faces +z
  b.addQuadGrid({ 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, 4, Vec3f(0.5f)); // faces +z too
  const Scene s = b.take();
  const LinkStructure one = linksOf(s, 64, false), two = linksOf(s, 64, true);
  const std::size_t nv = s.vertexCount();
  EXPECT_EQ(two.transport.rows(), 2 * nv);
  // Vertex 12 of the lower square (interior) looks up into the upper square's back.
  const std::size_t x = 6;
  EXPECT_LT(rowSum(one.transport, x), 1e-6f);
  EXPECT_LT(rowSum(one.environment, x), kPi - 0.5f);
  float toBacks = 0.f;
  for (Index i = two.transport.rowOffsets[x]; i < two.transport.rowOffsets[x + 1]; ++i)
  {
    EXPECT_GE(two.transport.columns[i], nv);
    toBacks += two.transport.weights[i];
  }
  EXPECT_NEAR(toBacks + rowSum(two.environment, x), kPi, 1e-4f);
}

TEST(TestLinks, RowsOfEveryBandAreWhereTheHitsPutThem)
{
  // The compression appends its rows to the CSR band by band (about 32 bands of chunks of
  // 64 rows): on a mesh of 32 bands every row must hold exactly the links its own hits make.
  // The squares face each other, so a front row's rays land on the other square's front
  // (vertex columns, barycentric weights) or leave past its edge, and a back row's all leave.
  const Scene s = test::twoSquares(false, 130);
  const std::size_t nv = s.vertexCount(), n = 4;
  ASSERT_GT(2 * nv, 32 * 2 * 64u); // bands of more than one chunk
  auto tracer = createCpuRayTracer();
  tracer->build(s.positions, s.triangles);
  const LinkOptions o{ std::uint32_t(n), true, true, 0 };
  const LinkHits hits =
    traceLinkRays(s, rayOrigins(s, Topology::build(nv, s.triangles)), *tracer, o);
  const LinkStructure l = compressLinks(s, hits, frontFaceNormals(s), o);
  ASSERT_EQ(l.transport.rows(), 2 * nv);
  ASSERT_EQ(l.environment.rows(), 2 * nv);
  const float w = kPi / float(n);
  for (std::size_t x = 0; x < 2 * nv; ++x)
  {
    std::map<Index, float> expected;
    int misses = 0;
    for (std::size_t k = 0; k < n; ++k)
    {
      const Hit& h = hits.hits[x * n + k];
      if (h.triangle == kInvalidIndex)
      {
        ++misses;
        continue;
      }
      ASSERT_LT(x, nv) << "a back side's ray hit the scene";
      const float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
      for (int j = 0; j < 3; ++j)
      {
        if (bary[j] > 0.f)
        {
          expected[s.triangles[h.triangle].v[j]] += w * bary[j];
        }
      }
    }
    std::map<Index, float> got;
    for (Offset i = l.transport.rowOffsets[x]; i < l.transport.rowOffsets[x + 1]; ++i)
    {
      got[l.transport.columns[i]] += l.transport.weights[i];
    }
    ASSERT_EQ(got.size(), expected.size()) << "row " << x;
    for (const auto& [column, weight] : expected)
    {
      ASSERT_EQ(got.count(column), 1u) << "row " << x << " column " << column;
      ASSERT_NEAR(got[column], weight, 1e-6f) << "row " << x << " column " << column;
    }
    ASSERT_NEAR(rowSum(l.environment, x), w * float(misses), 1e-5f) << "row " << x;
  }
}
