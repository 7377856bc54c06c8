// LinkGI engine: compile-time configuration shared by host and device code.
#pragma once

#if defined(__CUDACC__)
#define LINKGI_HOST_DEVICE __host__ __device__
#else
#define LINKGI_HOST_DEVICE
#endif

#include <cstdint>

namespace linkgi
{
/// Index type for vertices, triangles, elements and link columns: meshes of up to 4G elements.
using Index = std::uint32_t;
/// Counts and offsets of link entries: a mesh of 6.5M vertices at 256 rays has more than 2^32
/// links, so row offsets, non-zero counts and every sum over entry counts are 64-bit.
using Offset = std::uint64_t;
constexpr Index kInvalidIndex = 0xffffffffu;
constexpr float kPi = 3.14159265358979323846f;
}
