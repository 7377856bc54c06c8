#include "Primitives.h"

#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

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

void exclusiveSum(const Index* in, Index* out, std::size_t count, GPUBuffer<unsigned char>& temp,
  cudaStream_t stream)
{
  std::size_t bytes = 0;
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, count, stream));
  temp.resize(bytes);
  LINKGI_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, in, out, count, stream));
}
}
