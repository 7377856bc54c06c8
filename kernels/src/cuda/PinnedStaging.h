// Pinned host memory through which a stage's uploads and downloads go: copies from pinned
// memory are asynchronous and run at the link's speed, while pageable copies block the host
// and go through the driver's own staging.
#pragma once

#include "cuda/GPUBuffer.h"

#include "cpu/Parallel.h"

#include <cstring>
#include <vector>

namespace linkgi::cuda
{
class PinnedStaging
{
public:
  PinnedStaging() = default;
  ~PinnedStaging() { cudaFreeHost(data); }
  PinnedStaging(const PinnedStaging&) = delete;
  PinnedStaging& operator=(const PinnedStaging&) = delete;

  /// Starts a stage that will stage at most `bytes`; earlier copies must have completed.
  void begin(std::size_t bytes)
  {
    used = 0;
    if (bytes > capacity)
    {
      cudaFreeHost(data);
      data = nullptr;
      capacity = 0;
      void* p = nullptr;
      LINKGI_CUDA_CHECK(cudaMallocHost(&p, bytes + bytes / 4));
      data = static_cast<unsigned char*>(p);
      capacity = bytes + bytes / 4;
    }
  }
  /// Rounds a copy's size up to the 256 bytes each staged copy occupies.
  static std::size_t room(std::size_t bytes) { return (bytes + 255) / 256 * 256; }

  template <typename T>
  void upload(GPUBuffer<T>& to, const std::vector<T>& from, cudaStream_t stream)
  {
    const std::size_t bytes = from.size() * sizeof(T);
    if (used + room(bytes) > capacity)
    {
      to.upload(from, stream); // not reserved: a plain (pageable) copy
      return;
    }
    to.resize(from.size());
    unsigned char* at = data + used;
    copy(at, from.data(), bytes);
    used += room(bytes);
    if (bytes)
    {
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(to.data(), at, bytes, cudaMemcpyHostToDevice, stream));
    }
  }
  /// Queues a download of `bytes` from device memory; returns where it will land (valid
  /// after the stream is synchronised), or nullptr when not reserved.
  void* download(const void* from, std::size_t bytes, cudaStream_t stream)
  {
    if (used + room(bytes) > capacity)
    {
      return nullptr;
    }
    unsigned char* at = data + used;
    used += room(bytes);
    if (bytes)
    {
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(at, from, bytes, cudaMemcpyDeviceToHost, stream));
    }
    return at;
  }
  /// memcpy on all cores (a single thread copies ~10 GB/s; an upload is then the bottleneck).
  static void copy(void* to, const void* from, std::size_t bytes)
  {
    constexpr std::size_t kChunk = 1 << 20;
    parallelRanges((bytes + kChunk - 1) / kChunk, 1, [&](std::size_t begin, std::size_t end) {
      const std::size_t first = begin * kChunk, last = std::min(bytes, end * kChunk);
      std::memcpy(static_cast<unsigned char*>(to) + first, static_cast<const unsigned char*>(from) + first, last - first);
    });
  }

private:
  unsigned char* data = nullptr;
  std::size_t capacity = 0, used = 0;
};
}
