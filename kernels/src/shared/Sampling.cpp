#include "shared/Sampling.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace linkgi
{
std::uint32_t squareSide(std::uint32_t n)
{
  return static_cast<std::uint32_t>(std::lround(std::sqrt(double(n))));
}

bool isPerfectSquare(std::uint32_t n)
{
  const std::uint32_t k = squareSide(n);
  return n > 0 && k * k == n;
}

std::vector<Vec3f> makeDirectionSet(std::uint32_t n)
{
  if (!isPerfectSquare(n))
  {
    throw Error("The number of rays per vertex must be a perfect square (k*k, e.g. 64, 256, "
                "1024); got " + std::to_string(n) + ".");
  }
  const std::uint32_t k = squareSide(n);
  std::vector<Vec3f> dirs;
  dirs.reserve(n);
  for (std::uint32_t by = 0; by < k; by += 4)
  {
    for (std::uint32_t bx = 0; bx < k; bx += 4)
    {
      for (std::uint32_t y = by; y < std::min(by + 4, k); ++y)
      {
        for (std::uint32_t x = bx; x < std::min(bx + 4, k); ++x)
        {
          dirs.push_back(cosineHemisphere((x + 0.5f) / k, (y + 0.5f) / k));
        }
      }
    }
  }
  return dirs;
}
}
