// Hemisphere directions shared by every vertex, and the per-vertex twist.
#pragma once

#include "linkgi/Math.h"

#include <vector>

namespace linkgi
{
/// Shirley & Chiu's concentric map from [0,1)^2 to the unit disk: area-preserving and
/// low-distortion, so a stratified square gives a stratified disk.
LINKGI_HOST_DEVICE inline void concentricDisk(float u, float v, float& x, float& y)
{
  const float a = 2.f * u - 1.f, b = 2.f * v - 1.f;
  if (a == 0.f && b == 0.f)
  {
    x = y = 0.f;
    return;
  }
  float r, phi;
  if (a * a > b * b)
  {
    r = a;
    phi = (kPi / 4.f) * (b / a);
  }
  else
  {
    r = b;
    phi = (kPi / 2.f) - (kPi / 4.f) * (a / b);
  }
  x = r * std::cos(phi);
  y = r * std::sin(phi);
}

/// Cosine-weighted direction (z up) from a point of the unit square (Malley's method).
LINKGI_HOST_DEVICE inline Vec3f cosineHemisphere(float u, float v)
{
  float x, y;
  concentricDisk(u, v, x, y);
  const float z = std::sqrt(fmaxf(0.f, 1.f - x * x - y * y));
  return { x, y, z };
}

/// n = k*k cosine-weighted local directions at the centres of a k x k grid, ordered in 4x4
/// blocks of neighbouring cells so that consecutive rays (a SIMD packet, half a CUDA warp)
/// point in similar directions. k that is not a multiple of 4 gives partial blocks at the
/// border. Throws linkgi::Error unless n is a positive perfect square.
std::vector<Vec3f> makeDirectionSet(std::uint32_t n);

/// True if n = k*k for an integer k >= 1.
bool isPerfectSquare(std::uint32_t n);
/// k for n = k*k (the nearest integer to sqrt(n)).
std::uint32_t squareSide(std::uint32_t n);

/// Well-mixed 32-bit hash (lowbias32), for per-vertex random numbers that do not depend on
/// the thread schedule.
LINKGI_HOST_DEVICE inline std::uint32_t hash32(std::uint32_t x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/// A uniform number in [0,1) from (seed, index).
LINKGI_HOST_DEVICE inline float hashToUnit(std::uint32_t seed, std::uint32_t index)
{
  return (hash32(index ^ hash32(seed + 0x9e3779b9u)) >> 8) * (1.f / 16777216.f);
}

/// The frame in which vertex `v` shoots the shared direction set: the normal's frame,
/// rotated about the normal by a random twist angle when `twist` is set.
LINKGI_HOST_DEVICE inline Frame vertexFrame(const Vec3f& normal, bool twist, std::uint32_t seed, std::uint32_t v)
{
  Frame f = Frame::fromNormal(normal);
  if (twist)
  {
    const float phi = 2.f * kPi * hashToUnit(seed, v);
    const float c = std::cos(phi), s = std::sin(phi);
    const Vec3f t = f.t * c + f.b * s;
    f.b = f.t * (-s) + f.b * c;
    f.t = t;
  }
  return f;
}
}
