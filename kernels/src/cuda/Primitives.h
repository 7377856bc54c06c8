// Device-wide sort and scan (CUB), kept behind plain functions so that CUB's templates are
// compiled once, in Primitives.cu.
#pragma once

#include "cuda/GPUBuffer.h"

#include "linkgi/Config.h"

namespace linkgi::cuda
{
/// Radix sort of (key, value) pairs on key bits [0, endBit); stable. `temp` grows as needed.
void sortPairs(const std::uint64_t* keysIn, std::uint64_t* keysOut, const Index* valuesIn,
  Index* valuesOut, std::size_t count, int endBit, GPUBuffer<unsigned char>& temp,
  cudaStream_t stream);

/// Radix sort of keys on bits [0, endBit). `temp` grows as needed.
void sortKeys(const std::uint64_t* keysIn, std::uint64_t* keysOut, std::size_t count, int endBit,
  GPUBuffer<unsigned char>& temp, cudaStream_t stream);

/// out[i] = in[0] + ... + in[i-1], summed in 64 bits (entry counts pass 2^32).
void exclusiveSum(const Index* in, Offset* out, std::size_t count, GPUBuffer<unsigned char>& temp,
  cudaStream_t stream);

/// out[i] = in[0] + ... + in[i-1] of 64-bit values (e.g. two 32-bit counts packed in one).
void exclusiveSum(const std::uint64_t* in, std::uint64_t* out, std::size_t count,
  GPUBuffer<unsigned char>& temp, cudaStream_t stream);
}
