// The link-structure method on the CPU: Embree (or our BVH) and all cores.
#include "methods/links/LinksBackends.h"

#include "cpu/CpuGeometry.h"

#include "shared/Bounce.h"
#include "linkgi/Error.h"
#include "shared/DirectLight.h"
#include "methods/links/Links.h"
#include "linkgi/Memory.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace linkgi::links
{
namespace
{
using namespace engine;

class LinksCpu final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    switch (stage)
    {
      case kGeometryStage:
        return updateGeometry(c);
      case kLinkStage:
        return buildLinks(c);
      case kLightLinkStage:
        return lightLinks(c);
      case kBounceStage:
        return bounce(c);
    }
  }

  void commit() override
  {
    if (linksStaged)
    {
      std::swap(links, nextLinks);
      nextLinks = LinkStructure();
    }
    if (directStaged)
    {
      std::swap(direct, nextDirect);
      std::swap(nodeDirect, nextNodeDirect);
    }
    linksStaged = directStaged = geometryTouched = linksDropped = false;
  }

  bool discard() override
  {
    linksStaged = directStaged = false;
    // The tracer and the host geometry are updated in place: after a failure they may
    // belong to the failed scene, and the next update must rebuild them.
    const bool whole = !geometryTouched && !linksDropped;
    geometryTouched = linksDropped = false;
    return whole;
  }

  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.rays = links.rays;
    st.setCounter("LinksRaw", links.rawLinks);
    st.setCounter("LinksCompressed", links.transport.nonZeros());
    st.setCounter("LinksEnvironment", links.environment.nonZeros());
    st.setCounter("LinkBytes", links.transport.bytes() + links.environment.bytes());
    st.setCounter("DetailNodes", detail.nodes.size());
    st.lightRays = direct.shadowRays;
  }

  const RayTracer* sceneTracer() const override { return geometry.tracer.get(); }

  double sampleMemory(const StageContext& c) override
  {
    // Rows spread evenly over the mesh (a 64th of them, at least 256) linked as the stage
    // links them: their mean count of links, where the sizes alone give only the bound of
    // three per ray. At most 1.6% of the stage's rays, more on meshes under 16k elements.
    // Under MPI spread over this process's rows, their mean weighted by its share of rows.
    const SolverOptions& o = c.options;
    const std::size_t rows = Elements{ c.scene.vertexCount(), o.twoSided }.count();
    const std::uint8_t* own = ownRows(o, rows);
    const std::size_t mine = ownRowCount(o, rows);
    const std::size_t count = std::min(mine, std::max<std::size_t>(256, mine / 64));
    if (count == 0)
    {
      return 0.0;
    }
    std::vector<std::uint8_t> sample(rows, 0);
    for (std::size_t r = 0, ordinal = 0, k = 0; r < rows && k < count; ++r)
    {
      if (own && !own[r])
      {
        continue;
      }
      if (ordinal++ == k * mine / count) // the k-th of `count` own rows spread evenly
      {
        sample[r] = 1;
        ++k;
      }
    }
    const LinkOptions sampleOptions{ o.raysPerVertex, o.twoSided, o.twist, o.seed, sample.data(), &detail };
    const LinkStructure links =
      linkgi::buildLinks(c.scene, geometry.origins, *geometry.tracer, geometry.faceNormals, sampleOptions);
    const double share = double(mine) / double(rows);
    return share * double(links.transport.nonZeros() + links.environment.nonZeros()) / double(count);
  }

private:
  void updateGeometry(const StageContext& c)
  {
    geometryTouched = true;
    geometry.update(c);
    detail = detailNodes(c.scene, detailNodeBudget(c.scene.vertexCount()));
  }


  void buildLinks(const StageContext& c)
  {
    const SolverOptions& o = c.options;
    const LinkOptions linkOptions{ o.raysPerVertex, o.twoSided, o.twist, o.seed,
      ownRows(o, Elements{ c.scene.vertexCount(), o.twoSided }.count()), &detail };
    const auto within = [&c](double lo, double hi) -> ProgressCallback {
      return [&c, lo, hi](const char*, double f) { return !c.progress || c.progress("Links", lo + (hi - lo) * f); };
    };
    // Traced and compressed element by element: no buffer of every hit (4 KB per element
    // at 256 rays, held between updates before). The links being replaced go first, so that
    // a re-link holds one set of links at its peak, not the old and the new side by side; a
    // failed re-link then has none to keep (discard), and the next update links again.
    if (!links.transport.rowOffsets.empty())
    {
      links = LinkStructure();
      linksDropped = true;
      returnFreedMemory();
    }
    double msCompress = 0.0;
    nextLinks = linkgi::buildLinks(c.scene, geometry.origins, *geometry.tracer, geometry.faceNormals, linkOptions, within(0.0, 1.0), &msCompress);
    c.part("Compress", msCompress);
    linksStaged = true;
  }

  void lightLinks(const StageContext& c)
  {
    nextDirect = computeDirectLight(c.scene, geometry.topology, geometry.origins, *geometry.tracer, c.options.twoSided,
      c.options.lightOversampling, c.progress);
    nextNodeDirect = detailNodeDirect(c.scene, detail, geometry.origins, geometry.faceNormals, *geometry.tracer,
      c.options.twoSided, &nextDirect.shadowRays);
    directStaged = true;
  }

  void bounce(const StageContext& c)
  {
    const Scene& s = c.scene;
    const SolverOptions& o = c.options;
    const LinkStructure& linksNow = linksStaged ? nextLinks : links;
    const DirectLightResult& directNow = directStaged ? nextDirect : direct;
    const std::vector<Vec3f>& nodeDirectNow = directStaged ? nextNodeDirect : nodeDirect;
    const Elements elements{ s.vertexCount(), o.twoSided };
    const std::size_t ne = elements.count();

    const std::vector<Vec3f> texels = environmentTexelRadiance(s.environment);
    std::vector<Vec3f> envIrradiance(ne);
    gatherRgb(linksNow.environment, texels.data(), envIrradiance.data());
    const bool partitioned = ownRows(o, ne) != nullptr;
    if (partitioned)
    {
      o.partition->exchange(envIrradiance);
    }
    BounceInputs inputs;
    inputs.fixedIrradiance.resize(ne);
    inputs.albedo.resize(ne);
    for (std::size_t e = 0; e < ne; ++e)
    {
      inputs.fixedIrradiance[e] = directNow.irradiance[e] + envIrradiance[e];
      inputs.albedo[e] = s.albedo[elements.vertexOf(e)];
    }
    if (!s.emission.empty())
    {
      // Emissive surfaces emit from their front side only.
      inputs.emission.assign(ne, Vec3f(0.f));
      std::copy(s.emission.begin(), s.emission.end(), inputs.emission.begin());
    }
    // Detail nodes: their corners' radiance without the corners' direct light, and their own.
    inputs.extraColumns = detail.columns(o.twoSided);
    inputs.extraRadiance = [&](Vec3f* radiance) {
      detailNodeRadiance(s, detail, o.twoSided, directNow.irradiance.data(), nodeDirectNow.data(), ne, radiance);
    };
    std::vector<Vec3f> indirect = iterateBounces(linksNow.transport, inputs, o.bounces, c.progress,
      exchangeOf(o));
    for (std::size_t e = 0; e < ne; ++e)
    {
      indirect[e] += envIrradiance[e];
    }
    finishSolution(c, geometry.topology, std::move(indirect), directNow.irradiance);
  }

  CpuGeometry geometry;
  bool geometryTouched = false;
  LinkStructure links, nextLinks;
  bool linksDropped = false; ///< the cached links were freed for a re-link that has not committed
  DetailNodes detail;
  DirectLightResult direct, nextDirect;
  std::vector<Vec3f> nodeDirect, nextNodeDirect; ///< detailNodeDirect, staged as E_d
  bool linksStaged = false, directStaged = false;
};
}

std::uint64_t detailColumnBound(const MemoryShape& shape, const SolverOptions& o)
{
  return std::uint64_t(detailNodeBound(shape.vertices, shape.triangles)) * (o.twoSided ? 2 : 1);
}

LinksPerElement linksPerElement(const MemoryShape& shape, const SolverOptions& o)
{
  return LinksPerElement::bound(o.raysPerVertex,
    shape.vertices * (o.twoSided ? 2 : 1) + detailColumnBound(shape, o), shape.texels);
}

double estimatedLinksPerRow(const MemoryShape& shape, const SolverOptions& o)
{
  // The sample's rows are spread evenly over the mesh: on the standard scenes its mean is
  // within 1.2% of the whole mesh's (TestMemoryBudget.TheSampledRowsLinkAsTheWholeMeshDoes).
  constexpr double kSampleMargin = 1.1;
  const LinksPerElement bound = linksPerElement(shape, o);
  const double most = double(bound.transport + bound.environment);
  return shape.sampledPerElement > 0.0 ? std::min(most, kSampleMargin * shape.sampledPerElement) : most;
}

MemoryEstimate estimateCpuMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale)
{
  const std::uint64_t e = shape.vertices * (o.twoSided ? 2 : 1);
  const std::uint64_t n = o.raysPerVertex;
  constexpr std::uint64_t vec3 = sizeof(Vec3f), csrEntry = sizeof(Index) + sizeof(float);
  std::uint64_t bytes = 0;
  // The detail nodes at their bound: their grids and nodes with the geometry, their E_d
  // with the light links, their radiance in the bounces.
  const std::uint64_t nodeColumns = detailColumnBound(shape, o);
  if (stale & (1u << kGeometryStage))
  {
    bytes += cpuGeometryBytes(shape) + shape.triangles * (sizeof(Index) + sizeof(std::uint16_t)) +
      nodeColumns / (o.twoSided ? 2 : 1) * sizeof(DetailNode);
  }
  if (stale & (1u << kLinkStage))
  {
    // buildLinks: the CSR (linkRows reserves it at the links' bound; only the links
    // written become resident); a band's chunk buffers (a 32nd of the rows, at most 512
    // chunks of 64) with their vectors' growth; the row counts and offsets; per worker a
    // dense scratch row, one element's rays, hits and links to detail nodes.
    const std::uint64_t perRow = std::uint64_t(std::ceil(estimatedLinksPerRow(shape, o) * double(csrEntry)));
    const std::uint64_t perElement = perRow + 2 * (sizeof(Index) + sizeof(Offset));
    const std::uint64_t bandRows = std::min<std::uint64_t>({ e, e / 32 + 64, 512 * 64 });
    const std::uint64_t perWorker = (e + shape.texels) * sizeof(float) +
      n * (sizeof(Hit) + sizeof(Ray) + 3 * sizeof(std::pair<Index, float>));
    bytes += bandRows * perRow * 2;
    bytes += e * perElement + std::uint64_t(workerCount()) * perWorker;
  }
  if (stale & (1u << kLightLinkStage))
  {
    bytes += (e + nodeColumns) * vec3 * 2; // E_d, staged beside the cached one
  }
  // Bounces: the environment's irradiance, the fixed irradiance, albedo, emission, two
  // Jacobi vectors, the smoothed copy and the solution's three arrays.
  bytes += e * vec3 * 10 + nodeColumns * vec3;
  return { bytes, 0 };
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<LinksCpu>();
}
}
