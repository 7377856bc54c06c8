// Small vector math for the engine; compiles for host and device.
#pragma once

#include "linkgi/Config.h"

#include <cmath>

namespace linkgi
{
struct Vec3f
{
  float x = 0.f, y = 0.f, z = 0.f;

  LINKGI_HOST_DEVICE constexpr Vec3f() = default;
  LINKGI_HOST_DEVICE constexpr Vec3f(float a, float b, float c) : x(a), y(b), z(c) {}
  LINKGI_HOST_DEVICE explicit constexpr Vec3f(float s) : x(s), y(s), z(s) {}

  LINKGI_HOST_DEVICE float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  LINKGI_HOST_DEVICE float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  LINKGI_HOST_DEVICE Vec3f& operator+=(const Vec3f& b) { x += b.x; y += b.y; z += b.z; return *this; }
  LINKGI_HOST_DEVICE Vec3f& operator-=(const Vec3f& b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  LINKGI_HOST_DEVICE Vec3f& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
};

LINKGI_HOST_DEVICE inline Vec3f operator+(Vec3f a, const Vec3f& b) { return a += b; }
LINKGI_HOST_DEVICE inline Vec3f operator-(Vec3f a, const Vec3f& b) { return a -= b; }
LINKGI_HOST_DEVICE inline Vec3f operator-(const Vec3f& a) { return { -a.x, -a.y, -a.z }; }
LINKGI_HOST_DEVICE inline Vec3f operator*(Vec3f a, float s) { return a *= s; }
LINKGI_HOST_DEVICE inline Vec3f operator*(float s, Vec3f a) { return a *= s; }
LINKGI_HOST_DEVICE inline Vec3f operator/(const Vec3f& a, float s) { return a * (1.f / s); }
/// Component-wise product (colours).
LINKGI_HOST_DEVICE inline Vec3f operator*(const Vec3f& a, const Vec3f& b)
{
  return { a.x * b.x, a.y * b.y, a.z * b.z };
}
LINKGI_HOST_DEVICE inline bool operator==(const Vec3f& a, const Vec3f& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
LINKGI_HOST_DEVICE inline bool operator!=(const Vec3f& a, const Vec3f& b) { return !(a == b); }

LINKGI_HOST_DEVICE inline float dot(const Vec3f& a, const Vec3f& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
LINKGI_HOST_DEVICE inline Vec3f cross(const Vec3f& a, const Vec3f& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
LINKGI_HOST_DEVICE inline float length(const Vec3f& a) { return std::sqrt(dot(a, a)); }
LINKGI_HOST_DEVICE inline Vec3f normalize(const Vec3f& a)
{
  const float l = length(a);
  return l > 0.f ? a / l : Vec3f(0.f);
}
LINKGI_HOST_DEVICE inline float maxComponent(const Vec3f& a)
{
  return fmaxf(a.x, fmaxf(a.y, a.z));
}
/// Rec. 709 luminance of a linear RGB value.
LINKGI_HOST_DEVICE inline float luminance(const Vec3f& c)
{
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
LINKGI_HOST_DEVICE inline bool isFinite(const Vec3f& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
struct Frame
{
  Vec3f t, b, n;

  LINKGI_HOST_DEVICE static Frame fromNormal(const Vec3f& n)
  {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float bb = n.x * n.y * a;
    Frame f;
    f.t = { 1.f + sign * n.x * n.x * a, sign * bb, -sign * n.x };
    f.b = { bb, sign + n.y * n.y * a, -n.y };
    f.n = n;
    return f;
  }
  /// Local (x, y, z) with z along the normal to world space.
  LINKGI_HOST_DEVICE Vec3f toWorld(const Vec3f& l) const { return t * l.x + b * l.y + n * l.z; }
};
}
