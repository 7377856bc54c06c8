#include "BenchSolutions.h"

#include "linkgi/Error.h"
#include "shared/Metrics.h"

#include <fstream>
#include <sstream>

namespace linkgi::bench
{
void writeSolution(const std::string& path, const Solution& s)
{
  std::ofstream f(path, std::ios::binary);
  const std::uint64_t n = s.elementCount();
  f.write(reinterpret_cast<const char*>(&n), sizeof(n));
  for (const auto* v : { &s.direct, &s.indirect, &s.radiance })
  {
    f.write(reinterpret_cast<const char*>(v->data()), std::streamsize(n * sizeof(Vec3f)));
  }
  if (!f)
  {
    throw Error("Could not write " + path + ".");
  }
}

Solution readSolution(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  std::uint64_t n = 0;
  f.read(reinterpret_cast<char*>(&n), sizeof(n));
  Solution s;
  for (auto* v : { &s.direct, &s.indirect, &s.radiance })
  {
    v->resize(n);
    f.read(reinterpret_cast<char*>(v->data()), std::streamsize(n * sizeof(Vec3f)));
  }
  if (!f)
  {
    throw Error("Could not read " + path + ".");
  }
  return s;
}

std::string agreement(const Scene& scene, const Solution& a, const Solution& reference)
{
  const std::vector<float> areas = vertexAreas(scene), ones(areas.size(), 1.f);
  std::ostringstream json;
  json << "{";
  const char* names[] = { "direct", "indirect", "radiance" };
  const std::vector<Vec3f>* mine[] = { &a.direct, &a.indirect, &a.radiance };
  const std::vector<Vec3f>* theirs[] = { &reference.direct, &reference.indirect, &reference.radiance };
  for (int k = 0; k < 3; ++k)
  {
    const ErrorMetrics aw = relativeRmse(*mine[k], *theirs[k], areas);
    const ErrorMetrics pv = relativeRmse(*mine[k], *theirs[k], ones);
    json << (k ? "," : "") << "\"" << names[k] << "_aw\":" << maxComponent(aw.relRmse) << ",\""
         << names[k] << "_pv\":" << maxComponent(pv.relRmse);
  }
  json << "}";
  return json.str();
}
}
