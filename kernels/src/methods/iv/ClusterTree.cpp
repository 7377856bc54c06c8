#include "methods/iv/ClusterTree.h"

#include "cpu/Parallel.h"
#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>

namespace linkgi::iv
{
namespace
{
/// Normals in a range that spread by more than this (a component's range; 0.5 is about
/// 30 degrees) are split by orientation first, so a cluster does not wrap a corner.
constexpr float kNormalSpread = 0.5f;

struct Builder
{
  const Scene& scene;
  ClusterTree& tree;
  std::vector<Index> order;

  /// The node for order[begin, end): leaves are vertices, interior nodes get the next id
  /// after both children (post-order).
  Index split(std::size_t begin, std::size_t end)
  {
    if (end - begin == 1)
    {
      return order[begin];
    }
    Vec3f lo(3e38f), hi(-3e38f), nlo(3e38f), nhi(-3e38f);
    for (std::size_t i = begin; i < end; ++i)
    {
      const Vec3f& p = scene.positions[order[i]];
      const Vec3f& n = scene.normals[order[i]];
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
        nlo[k] = std::min(nlo[k], n[k]);
        nhi[k] = std::max(nhi[k], n[k]);
      }
    }
    int axis = 0;
    bool byNormal = false;
    float widest = -1.f;
    for (int k = 0; k < 3; ++k)
    {
      if (nhi[k] - nlo[k] > kNormalSpread && nhi[k] - nlo[k] > widest)
      {
        widest = nhi[k] - nlo[k];
        axis = k;
        byNormal = true;
      }
    }
    if (!byNormal)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (hi[k] - lo[k] > widest)
        {
          widest = hi[k] - lo[k];
          axis = k;
        }
      }
    }
    const std::vector<Vec3f>& key = byNormal ? scene.normals : scene.positions;
    const std::size_t mid = begin + (end - begin) / 2;
    // Ties broken by vertex index: the structure is a function of the input alone.
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
      [&](Index a, Index b) { return key[a][axis] < key[b][axis] || (key[a][axis] == key[b][axis] && a < b); });
    const Index l = split(begin, mid);
    const Index r = split(mid, end);
    const Index id = Index(tree.leafCount + tree.left.size());
    tree.left.push_back(l);
    tree.right.push_back(r);
    return id;
  }
};

float angleBetween(const Vec3f& a, const Vec3f& b)
{
  return std::acos(std::clamp(dot(a, b), -1.f, 1.f));
}
}

ClusterTree ClusterTree::build(const Scene& scene, const std::vector<float>& areas)
{
  const std::size_t n = scene.vertexCount();
  if (n == 0)
  {
    throw Error("The implicit-visibility hierarchy needs at least one vertex.");
  }
  ClusterTree tree;
  tree.leafCount = n;
  tree.left.reserve(n - 1);
  tree.right.reserve(n - 1);
  Builder b{ scene, tree, std::vector<Index>(n) };
  for (std::size_t i = 0; i < n; ++i)
  {
    b.order[i] = Index(i);
  }
  b.split(0, n);
  tree.parent.assign(2 * n - 1, kInvalidIndex);
  for (std::size_t i = 0; i < tree.left.size(); ++i)
  {
    tree.parent[tree.left[i]] = tree.parent[tree.right[i]] = Index(n + i);
  }
  tree.refit(scene, areas);
  return tree;
}

void ClusterTree::refit(const Scene& scene, const std::vector<float>& areas)
{
  if (scene.vertexCount() != leafCount || areas.size() != leafCount)
  {
    throw Error("The implicit-visibility hierarchy was built for " + std::to_string(leafCount) +
      " vertices; refit got " + std::to_string(scene.vertexCount()) + ".");
  }
  const std::size_t nodes = 2 * leafCount - 1;
  position.resize(nodes);
  normal.resize(nodes);
  area.resize(nodes);
  radius.resize(nodes);
  coneAngle.resize(nodes);
  planeDeviation.resize(nodes);
  extent.resize(leafCount);
  extentSlab.resize(leafCount);
  for (std::size_t v = 0; v < leafCount; ++v)
  {
    position[v] = scene.positions[v];
    normal[v] = scene.normals[v];
    area[v] = areas[v];
    radius[v] = std::sqrt(areas[v] / kPi);
    coneAngle[v] = 0.f;
    planeDeviation[v] = 0.f;
    extent[v] = radius[v];
    extentSlab[v] = 0.f;
  }
  // Each triangle's corners in parallel, then the vertices' maxima in one pass.
  const std::size_t nt = scene.triangles.size();
  std::vector<float> cornerExtent(3 * nt), cornerSlab(3 * nt);
  parallelRanges(nt, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      const Triangle& tri = scene.triangles[t];
      const Vec3f p[3] = { scene.positions[tri.v[0]], scene.positions[tri.v[1]], scene.positions[tri.v[2]] };
      const Vec3f centroid = (p[0] + p[1] + p[2]) * (1.f / 3.f);
      for (int k = 0; k < 3; ++k)
      {
        const Vec3f& a = p[k];
        const Vec3f& n = normal[tri.v[k]];
        const Vec3f corners[3] = { centroid - a, 0.5f * (p[(k + 1) % 3] - a), 0.5f * (p[(k + 2) % 3] - a) };
        float e = 0.f, slab = 0.f;
        for (const Vec3f& q : corners)
        {
          e = std::max(e, length(q));
          slab = std::max(slab, std::abs(dot(n, q)));
        }
        cornerExtent[3 * t + k] = e;
        cornerSlab[3 * t + k] = slab;
      }
    }
  });
  for (std::size_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Index v = scene.triangles[t].v[k];
      extent[v] = std::max(extent[v], cornerExtent[3 * t + k]);
      extentSlab[v] = std::max(extentSlab[v], cornerSlab[3 * t + k]);
    }
  }
  for (std::size_t i = 0; i < left.size(); ++i)
  {
    const std::size_t id = leafCount + i;
    const Index c[2] = { left[i], right[i] };
    const float a = area[c[0]] + area[c[1]];
    area[id] = a;
    position[id] = a > 0.f ? (position[c[0]] * area[c[0]] + position[c[1]] * area[c[1]]) / a
                           : (position[c[0]] + position[c[1]]) * 0.5f;
    Vec3f n = normalize(normal[c[0]] * area[c[0]] + normal[c[1]] * area[c[1]]);
    if (dot(n, n) == 0.f)
    {
      n = normalize(normal[c[0]] + normal[c[1]]);
    }
    normal[id] = dot(n, n) == 0.f ? normal[c[0]] : n;
    float r = 0.f, cone = 0.f, slab = 0.f;
    for (Index k : c)
    {
      const Vec3f d = position[k] - position[id];
      r = std::max(r, length(d) + radius[k]);
      cone = std::max(cone, std::min(kPi, angleBetween(normal[id], normal[k]) + coneAngle[k]));
      // A child's points lie within its slab along its normal and its sphere across it.
      const float along = std::abs(dot(normal[id], normal[k]));
      const float across = std::sqrt(std::max(0.f, 1.f - along * along));
      slab = std::max(slab, std::abs(dot(normal[id], d)) + std::min(radius[k], along * planeDeviation[k] + across * radius[k]));
    }
    radius[id] = r;
    coneAngle[id] = cone;
    planeDeviation[id] = std::min(slab, r);
  }
}
}
