#include "methods/iv/ImplicitLinks.h"

#include "linkgi/Error.h"
#include "shared/Csr.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace linkgi::iv
{
namespace
{
/// Solid angle of the cube-face rectangle [0, x] x [0, y] at distance 1.
double cornerSolidAngle(double x, double y)
{
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

using Pair = std::pair<Index, Index>;

/// Links one task creates before it keeps only each receiver's shortest per bin (and then
/// again whenever they have grown by this much beyond what the last reduction kept).
constexpr std::size_t kLinksBeforeReduction = std::size_t(1) << 18;

/// Rows from (row, column) pairs: a counting sort, columns in the pairs' order.
SparseMatrix rowsOf(const std::vector<std::vector<Pair>>& parts, std::size_t rows)
{
  SparseMatrix m;
  std::vector<Index> counts(rows, 0);
  for (const auto& part : parts)
  {
    for (const Pair& p : part)
    {
      ++counts[p.first];
    }
  }
  exclusiveOffsets(counts, 0, m.rowOffsets);
  m.columns.resize(m.rowOffsets.back());
  std::vector<Offset> next(m.rowOffsets.begin(), m.rowOffsets.end() - 1);
  for (const auto& part : parts)
  {
    for (const Pair& p : part)
    {
      m.columns[next[p.first]++] = p.second;
    }
  }
  return m;
}


bool progressSays(const ProgressCallback& progress, double fraction)
{
  return !progress || progress("ImplicitLinks", fraction);
}

/// The paper's rule at creation for one receiving node at a time: each direction bin (seen
/// from the node) keeps only its shortest link, ties going to the lower source; links
/// without a direction are all kept. Its buffers are reused from node to node.
class ShortestPerBin
{
public:
  explicit ShortestPerBin(const CubeBins& bins)
    : BinAngle(std::sqrt(bins.meanSolidAngle()))
    , BestDistance(bins.count())
    , BestSource(bins.count(), kInvalidIndex)
  {
  }

  /// Offers the link from `source` to `node`; false for a link without a direction, or one
  /// to a leaf the push draws from its surface (keptWhole), which the caller keeps as it is.
  bool offer(const ClusterTree& t, const CubeBins& bins, Index node, Index source)
  {
    const Vec3f d = t.position[source] - t.position[node];
    const float d2 = dot(d, d);
    const bool leaf = t.isLeaf(source);
    if (!(d2 > 0.f) ||
      keptWhole(leaf, t.radius[source], leaf ? t.extent[source] : 0.f, t.normal[source], d, d2, this->BinAngle))
    {
      return false;
    }
    const int b = cubeBin(d, bins.n);
    if (this->BestSource[b] == kInvalidIndex)
    {
      this->Touched.push_back(b);
    }
    else if (d2 > this->BestDistance[b] || (d2 == this->BestDistance[b] && source > this->BestSource[b]))
    {
      return true;
    }
    this->BestDistance[b] = d2;
    this->BestSource[b] = source;
    return true;
  }

  /// Hands each bin's shortest source to `keep`, in bin order (deterministic), and resets.
  template <typename Keep>
  void take(Keep&& keep)
  {
    std::sort(this->Touched.begin(), this->Touched.end());
    for (int b : this->Touched)
    {
      keep(this->BestSource[b]);
      this->BestSource[b] = kInvalidIndex;
    }
    this->Touched.clear();
  }

private:
  float BinAngle;
  std::vector<float> BestDistance;
  std::vector<Index> BestSource;
  std::vector<int> Touched;
};

/// ShortestPerBin applied to each receiving node's links once all are created, in parallel.
void keepShortestPerBin(const ClusterTree& t, const CubeBins& bins, SparseMatrix& m,
  const ProgressCallback& progress)
{
  const std::size_t rows = m.rows();
  std::vector<Index> counts(rows, 0);
  parallelFor("ImplicitLinks", rows, 256, [&](std::size_t begin, std::size_t end) {
    ShortestPerBin shortest(bins);
    for (std::size_t node = begin; node < end; ++node)
    {
      Offset out = m.rowOffsets[node];
      for (Offset e = m.rowOffsets[node]; e < m.rowOffsets[node + 1]; ++e)
      {
        const Index src = m.columns[e];
        if (!shortest.offer(t, bins, Index(node), src))
        {
          m.columns[out++] = src; // no direction: kept
        }
      }
      shortest.take([&](Index src) { m.columns[out++] = src; });
      counts[node] = Index(out - m.rowOffsets[node]);
    }
  }, [&progress](const char*, double f) { return progressSays(progress, 0.8 + 0.2 * f); });
  // Compact the rows in place (each row only moves towards the front).
  Offset next = 0;
  for (std::size_t node = 0; node < rows; ++node)
  {
    const Offset first = m.rowOffsets[node];
    std::copy(m.columns.begin() + first, m.columns.begin() + first + counts[node], m.columns.begin() + next);
    m.rowOffsets[node] = next;
    next += counts[node];
  }
  m.rowOffsets[rows] = next;
  m.columns.resize(next);
}

/// Sorts part[from, end) by receiver, stably: least significant 16 bits first, then the
/// next 16 where receivers reach that far (an LSD radix sort; `scratch` is its buffer).
void radixSortByReceiver(std::vector<Pair>& part, std::size_t from, Index receivers, std::vector<Pair>& scratch)
{
  const std::size_t n = part.size() - from;
  scratch.resize(n);
  Pair* src = part.data() + from;
  Pair* dst = scratch.data();
  std::vector<std::size_t> offsets(std::size_t(1) << 16);
  for (int shift = 0; shift < 32 && (shift == 0 || (std::uint64_t(receivers) >> shift) > 0); shift += 16)
  {
    std::fill(offsets.begin(), offsets.end(), 0);
    for (std::size_t i = 0; i < n; ++i)
    {
      ++offsets[(src[i].first >> shift) & 0xffffu];
    }
    std::size_t sum = 0;
    for (std::size_t& o : offsets)
    {
      sum += std::exchange(o, sum);
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      dst[offsets[(src[i].first >> shift) & 0xffffu]++] = src[i];
    }
    std::swap(src, dst);
  }
  if (src != part.data() + from)
  {
    std::copy(src, src + n, part.data() + from);
  }
}

/// keepShortestPerBin on the links one task has created so far: grouped by receiver (in
/// their order otherwise), each receiver's bins keep their shortest link and links without
/// a direction stay. The final pass over all tasks' links then keeps what it would have kept
/// from all of them (a bin's shortest of the shortest is its shortest; ties go to the lower
/// source either way), so the result is the same, but the created links are never all held
/// at once: they are an order of magnitude more than the links kept.
/// part[0, sorted) is the last reduction's output, already grouped by receiver in order: only
/// the links after it are sorted, then merged behind it (what a stable sort of the whole
/// part gives, at a fraction of its cost).
void reducePart(const ClusterTree& t, const CubeBins& bins, std::vector<Pair>& part,
  std::size_t sorted, ShortestPerBin& shortest, std::vector<Pair>& scratch)
{
  radixSortByReceiver(part, sorted, Index(t.nodeCount()), scratch);
  std::inplace_merge(part.begin(), part.begin() + std::ptrdiff_t(sorted), part.end(),
    [](const Pair& a, const Pair& b) { return a.first < b.first; });
  std::size_t out = 0;
  for (std::size_t first = 0; first < part.size();)
  {
    const Index node = part[first].first;
    std::size_t last = first;
    for (; last < part.size() && part[last].first == node; ++last)
    {
      if (!shortest.offer(t, bins, node, part[last].second))
      {
        part[out++] = part[last];
      }
    }
    shortest.take([&](Index src) { part[out++] = Pair(node, src); });
    first = last;
  }
  part.resize(out);
  part.shrink_to_fit();
}
}

std::vector<NodeBounds> nodeBounds(const ClusterTree& t)
{
  std::vector<NodeBounds> nodes(t.nodeCount());
  parallelRanges(nodes.size(), 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      nodes[i] = { t.position[i], t.radius[i], t.normal[i], t.planeDeviation[i], t.coneAngle[i],
        std::sin(t.coneAngle[i]), std::cos(t.coneAngle[i]),
        t.isLeaf(Index(i)) ? kInvalidIndex : t.left[i - t.leafCount] };
    }
  });
  return nodes;
}

LinkCreationOptions LinkCreationOptions::of(const Scene& scene)
{
  LinkCreationOptions o;
  o.planeEpsilon = 0.1f * rayEpsilon(scene);
  return o;
}

PairRules pairRules(const NodeBounds* nodes, const Index* left, const Index* right, const float* extents,
  const float* extentSlabs, std::size_t leafCount, const CubeBins& bins, const LinkCreationOptions& options)
{
  PairRules r;
  r.nodes = nodes;
  r.extents = extents;
  r.extentSlabs = extentSlabs;
  r.left = left;
  r.right = right;
  r.leafCount = Index(leafCount);
  r.binSolidAngle = bins.meanSolidAngle();
  r.planeEpsilon = options.planeEpsilon;
  r.maxConeAngle = options.maxConeAngle;
  return r;
}

CubeBins CubeBins::make(int n)
{
  if (n < 1 || n > 64)
  {
    throw Error("Cube-map bins per face must be between 1 and 64 per side; got " + std::to_string(n) + ".");
  }
  CubeBins bins;
  bins.n = n;
  bins.center.resize(6 * std::size_t(n) * n);
  bins.solidAngle.resize(bins.center.size());
  for (int face = 0; face < 6; ++face)
  {
    for (int row = 0; row < n; ++row)
    {
      for (int col = 0; col < n; ++col)
      {
        const double u0 = 2.0 * col / n - 1.0, u1 = 2.0 * (col + 1) / n - 1.0;
        const double v0 = 2.0 * row / n - 1.0, v1 = 2.0 * (row + 1) / n - 1.0;
        const float u = float(0.5 * (u0 + u1)), v = float(0.5 * (v0 + v1));
        const float s = (face % 2 == 0) ? 1.f : -1.f;
        Vec3f c = face < 2 ? Vec3f(s, u, v) : face < 4 ? Vec3f(u, s, v) : Vec3f(u, v, s);
        const std::size_t bin = (std::size_t(face) * n + row) * n + col;
        bins.center[bin] = normalize(c);
        bins.solidAngle[bin] = float(cornerSolidAngle(u1, v1) - cornerSolidAngle(u0, v1) -
          cornerSolidAngle(u1, v0) + cornerSolidAngle(u0, v0));
      }
    }
  }
  return bins;
}

NodeLinks createNodeLinks(const ClusterTree& tree, const CubeBins& bins,
  const LinkCreationOptions& options, const ProgressCallback& progress, const std::uint8_t* rows,
  std::vector<Index>* createdPerReceiver)
{
  const std::vector<NodeBounds> nodes = nodeBounds(tree);
  PairRules rules = pairRules(nodes.data(), tree.left.data(), tree.right.data(), tree.extent.data(),
    tree.extentSlab.data(), tree.leafCount, bins, options);
  std::vector<std::uint8_t> ownBelow;
  if (rows)
  {
    // Children precede their parent: one pass in index order.
    ownBelow.assign(rows, rows + tree.leafCount);
    ownBelow.resize(tree.nodeCount(), 0);
    for (std::size_t i = 0; i < tree.left.size(); ++i)
    {
      ownBelow[tree.leafCount + i] = ownBelow[tree.left[i]] | ownBelow[tree.right[i]];
    }
    rules.ownBelow = ownBelow.data();
  }
  NodeLinks out;
  // Breadth-first from (root, root) until there are enough independent pairs for every
  // core; the links found on the way are the first part.
  std::vector<std::vector<Pair>> parts(1);
  std::vector<Pair> frontier{ { tree.root(), tree.root() } }, next;
  const std::size_t target = std::size_t(workerCount()) * 1024;
  while (!frontier.empty() && frontier.size() < target)
  {
    next.clear();
    auto emit = [&](Index r, Index s) { parts[0].emplace_back(r, s); };
    auto push = [&](Index a, Index b) { next.emplace_back(a, b); };
    for (const Pair& p : frontier)
    {
      rules.visit(p.first, p.second, emit, push);
    }
    out.pairsVisited += frontier.size();
    std::swap(frontier, next);
  }
  // Then depth first, one part per slice of the frontier: subtrees differ in size by orders
  // of magnitude, and 512 slices keep both cores busy between progress reports (64 left one
  // idle for a tenth of the time on the torso).
  const std::size_t slices = std::min<std::size_t>(frontier.size(), 512);
  parts.resize(1 + slices);
  std::vector<std::uint64_t> visited(slices, 0);
  parallelFor("ImplicitLinks", slices, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<Pair> stack;
    auto push = [&](Index a, Index b) { stack.emplace_back(a, b); };
    ShortestPerBin shortest(bins);
    std::vector<Pair> scratch;
    for (std::size_t s = begin; s < end; ++s)
    {
      std::vector<Pair>& part = parts[1 + s];
      std::size_t reduced = 0; // the part's size after its last reduction
      auto emit = [&](Index r, Index src) {
        part.emplace_back(r, src);
        if (part.size() >= 2 * reduced + kLinksBeforeReduction)
        {
          reducePart(tree, bins, part, reduced, shortest, scratch);
          reduced = part.size();
        }
      };
      std::uint64_t count = 0; // a local count: neighbouring slices' counters share a cache line
      for (std::size_t i = s * frontier.size() / slices; i < (s + 1) * frontier.size() / slices; ++i)
      {
        stack.push_back(frontier[i]);
        while (!stack.empty())
        {
          const Pair p = stack.back();
          stack.pop_back();
          ++count;
          rules.visit(p.first, p.second, emit, push);
        }
      }
      visited[s] = count;
      reducePart(tree, bins, part, reduced, shortest, scratch);
    }
  }, [&progress](const char*, double f) { return progressSays(progress, 0.8 * f); });
  for (std::uint64_t v : visited)
  {
    out.pairsVisited += v;
  }
  out.byReceiver = rowsOf(parts, tree.nodeCount());
  out.created = out.byReceiver.nonZeros();
  if (createdPerReceiver)
  {
    const std::vector<Offset>& r = out.byReceiver.rowOffsets;
    createdPerReceiver->resize(tree.nodeCount());
    for (std::size_t node = 0; node < tree.nodeCount(); ++node)
    {
      (*createdPerReceiver)[node] = Index(r[node + 1] - r[node]);
    }
  }
  keepShortestPerBin(tree, bins, out.byReceiver, progress);
  return out;
}


std::vector<Vec3f> iterateHierarchicalBounces(const ClusterTree& tree,
  const SparseMatrix& transport, const BounceInputs& inputs, std::uint32_t bounces,
  const ProgressCallback& progress, const std::function<void(std::vector<Vec3f>&)>& exchange)
{
  const std::size_t leaves = tree.leafCount;
  std::vector<Vec3f> indirect(leaves, Vec3f(0.f)), radiance(tree.nodeCount() + inputs.extraColumns);
  for (std::uint32_t b = 0; b < bounces; ++b)
  {
    if (progress && !progress("Bounces", double(b) / bounces))
    {
      throw Aborted();
    }
    parallelRanges(leaves, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t e = begin; e < end; ++e)
      {
        radiance[e] = outgoingRadiance(inputs.albedo[e], inputs.fixedIrradiance[e], indirect[e],
          inputs.emission.empty() ? Vec3f(0.f) : inputs.emission[e]);
      }
    });
    // Pull up: children precede their parent, so one pass in index order.
    for (std::size_t i = 0; i < tree.left.size(); ++i)
    {
      const std::size_t id = leaves + i;
      const Index l = tree.left[i], r = tree.right[i];
      radiance[id] = tree.area[id] > 0.f
        ? (radiance[l] * tree.area[l] + radiance[r] * tree.area[r]) / tree.area[id]
        : Vec3f(0.f);
    }
    if (inputs.extraColumns)
    {
      inputs.extraRadiance(radiance.data());
    }
    gatherRgb(transport, radiance.data(), indirect.data());
    if (exchange)
    {
      exchange(indirect);
    }
  }
  return indirect;
}
}
