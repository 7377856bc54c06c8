#include "linkgi/Memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace linkgi
{
namespace
{
/// The value of `key` (in kB) in a /proc file of "Key:   123 kB" lines, in bytes; 0 if absent.
std::uint64_t procKilobytes(const char* file, const std::string& key)
{
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() && line[key.size()] == ':')
    {
      std::istringstream value(line.substr(key.size() + 1));
      std::uint64_t kb = 0;
      value >> kb;
      return kb * 1024;
    }
  }
  return 0;
}
}

MemoryShape MemoryShape::of(const Scene& scene)
{
  MemoryShape shape;
  shape.vertices = scene.vertexCount();
  shape.triangles = scene.triangleCount();
  shape.texels = scene.environment.hasTexture() ? scene.environment.texels.size() : 1;
  return shape;
}

namespace
{
std::atomic<std::uint64_t> availableOverride{ 0 };
}

std::uint64_t availableHostBytes()
{
  const std::uint64_t forced = availableOverride.load();
  return forced ? forced : procKilobytes("/proc/meminfo", "MemAvailable");
}

void overrideAvailableHostBytes(std::uint64_t bytes)
{
  availableOverride = bytes;
}

std::uint64_t hostMemoryBudget(std::uint64_t requested)
{
  if (requested > 0)
  {
    return requested;
  }
  const std::uint64_t available = availableHostBytes();
  if (available == 0)
  {
    return std::numeric_limits<std::uint64_t>::max();
  }
  const std::uint64_t margin = std::max<std::uint64_t>(available / 10, std::uint64_t(512) << 20);
  return available > margin ? available - margin : 0;
}

std::string formatBytes(std::uint64_t bytes)
{
  const char* units[] = { "B", "KiB", "MiB", "GiB", "TiB" };
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4)
  {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : value < 10.0 ? "%.2f %s" : "%.1f %s", value, units[unit]);
  return text;
}

std::uint64_t peakResidentBytes()
{
  return procKilobytes("/proc/self/status", "VmHWM");
}

std::uint64_t residentBytes()
{
  return procKilobytes("/proc/self/status", "VmRSS");
}

bool resetPeakResident()
{
  // "5" resets the peak resident set to the current one (proc(5), clear_refs).
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return bool(out);
}
}

void linkgi::returnFreedMemory()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}
