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
/// Index type for vertices, triangles and links. 32 bits covers meshes of up to 4G elements.
using Index = std::uint32_t;
constexpr Index kInvalidIndex = 0xffffffffu;
constexpr float kPi = 3.14159265358979323846f;
}
