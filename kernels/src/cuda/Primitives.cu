#include "cuda/Primitives.h"

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <cuda/std/functional>

namespace linkgi::cuda
{
void sortPairs(const std::uint64_t* keysIn, std::uint64_t* keysOut, const Index* valuesIn,
  Index* valuesOut, std::size_t count, int endBit, GPUBuffer<unsigned char>& temp,
  cudaStream_t stream)
{
  std::size_t bytes = 0;
  LINKGI_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keysIn, keysOut, valuesIn,
    valuesOut, count, 0, endBit, stream));
  temp.resize(bytes);
  LINKGI_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp.data(), bytes, keysIn, keysOut, valuesIn,
    valuesOut, count, 0, endBit, stream));
}

void sortKeys(const std::uint64_t* keysIn, std::uint64_t* keysOut, std::size_t count, int endBit,
  GPUBuffer<unsigned char>& temp, cudaStream_t stream)
{
  std::size_t bytes = 0;
  LINKGI_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(nullptr, bytes, keysIn, keysOut, count, 0, endBit, stream));
  temp.resize(bytes);
  LINKGI_CUDA_CHECK(cub::DeviceRadixSort::SortKeys(temp.data(), bytes, keysIn, keysOut, count, 0, endBit, stream));
}

void exclusiveSum(const Index* in, Offset* out, std::size_t count, GPUBuffer<unsigned char>& temp,
  cudaStream_t stream)
{
  // The 64-bit initial value makes CUB accumulate in 64 bits (Sum(Offset, Index) = Offset).
  std::size_t bytes = 0;
  const auto sum = ::cuda::std::plus<>{};
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveScan(nullptr, bytes, in, out, sum, Offset(0), count, stream));
  temp.resize(bytes);
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveScan(temp.data(), bytes, in, out, sum, Offset(0), count, stream));
}

void exclusiveSum(const std::uint64_t* in, std::uint64_t* out, std::size_t count,
  GPUBuffer<unsigned char>& temp, cudaStream_t stream)
{
  std::size_t bytes = 0;
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, count, stream));
  temp.resize(bytes);
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, in, out, count, stream));
}
}
