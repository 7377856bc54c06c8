// GPUBuffer<T>: device memory owned like a std::vector, on the device that was current at
// allocation (and freed there).
#pragma once

#include "cuda/CudaCheck.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <utility>
#include <vector>

namespace linkgi::cuda
{
/// Device memory held by GPUBuffers, per device and in all: what the engine allocated, not
/// cudaMemGetInfo's view of the device (which counts the CUDA context and other processes).
class MemoryLedger
{
public:
  static constexpr int kDevices = 64;
  static void add(int device, std::size_t bytes)
  {
    perDevice()[device & (kDevices - 1)] += bytes;
    const std::size_t now = total() += bytes;
    std::size_t seen = peak().load();
    while (now > seen && !peak().compare_exchange_weak(seen, now))
    {
    }
  }
  static void remove(int device, std::size_t bytes)
  {
    perDevice()[device & (kDevices - 1)] -= bytes;
    total() -= bytes;
  }
  static std::size_t held(int device) { return perDevice()[device & (kDevices - 1)].load(); }
  static std::size_t held() { return total().load(); }
  /// The largest sum over all devices since the last call; starts the next period at the
  /// current sum.
  static std::size_t takePeak() { return peak().exchange(total().load()); }

private:
  static std::atomic<std::size_t>* perDevice()
  {
    static std::atomic<std::size_t> bytes[kDevices] = {};
    return bytes;
  }
  static std::atomic<std::size_t>& total()
  {
    static std::atomic<std::size_t> bytes{ 0 };
    return bytes;
  }
  static std::atomic<std::size_t>& peak()
  {
    static std::atomic<std::size_t> bytes{ 0 };
    return bytes;
  }
};

template <typename T>
class GPUBuffer
{
public:
  GPUBuffer() = default;
  explicit GPUBuffer(std::size_t count) { resize(count); }
  ~GPUBuffer() { release(); }
  GPUBuffer(const GPUBuffer&) = delete;
  GPUBuffer& operator=(const GPUBuffer&) = delete;
  GPUBuffer(GPUBuffer&& o) noexcept { swap(o); }
  GPUBuffer& operator=(GPUBuffer&& o) noexcept
  {
    if (this != &o)
    {
      release();
      swap(o);
    }
    return *this;
  }

  /// Discards the contents; keeps the allocation when it is large enough. A buffer that
  /// has to grow gets a quarter more than asked: sizes that creep up from update to update
  /// (a GPU's share of the links) then do not pay a cudaFree + cudaMalloc every time.
  void resize(std::size_t count)
  {
    if (count > capacity_)
    {
      const std::size_t capacity = capacity_ ? count + count / 4 : count;
      release();
      void* p = nullptr;
      LINKGI_CUDA_CHECK(cudaGetDevice(&device_));
      LINKGI_CUDA_CHECK(allocate(&p, capacity * sizeof(T)));
      data_ = static_cast<T*>(p);
      capacity_ = capacity;
      MemoryLedger::add(device_, capacity * sizeof(T));
    }
    size_ = count;
  }

  /// Grows to at least `count` elements keeping the first size() (capacity at least doubles,
  /// so appending batch by batch reallocates rarely); size() becomes `count`.
  void growKeep(std::size_t count, cudaStream_t stream)
  {
    if (count > capacity_)
    {
      GPUBuffer bigger;
      bigger.resize(std::max(count, 2 * capacity_));
      if (size_)
      {
        LINKGI_CUDA_CHECK(cudaMemcpyAsync(bigger.data_, data_, size_ * sizeof(T), cudaMemcpyDeviceToDevice, stream));
        LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
      }
      swap(bigger);
    }
    size_ = count;
  }

  void upload(const T* host, std::size_t count, cudaStream_t stream = nullptr)
  {
    resize(count);
    if (count)
    {
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(data_, host, count * sizeof(T), cudaMemcpyHostToDevice, stream));
    }
  }
  void upload(const std::vector<T>& host, cudaStream_t stream = nullptr)
  {
    upload(host.data(), host.size(), stream);
  }
  /// Synchronous copy of the first `count` elements to the host.
  void download(T* host, std::size_t count) const
  {
    if (count)
    {
      LINKGI_CUDA_CHECK(cudaMemcpy(host, data_, count * sizeof(T), cudaMemcpyDeviceToHost));
    }
  }
  std::vector<T> download() const
  {
    std::vector<T> host(size_);
    download(host.data(), size_);
    return host;
  }
  void fillZero(cudaStream_t stream = nullptr)
  {
    if (size_)
    {
      LINKGI_CUDA_CHECK(cudaMemsetAsync(data_, 0, size_ * sizeof(T), stream));
    }
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return capacity_ * sizeof(T); }
  bool empty() const { return size_ == 0; }

  void swapWith(GPUBuffer& o) noexcept { swap(o); }

  void release()
  {
    if (data_)
    {
      int current = 0;
      // Free on the owning device; errors here cannot be reported from a destructor.
      cudaGetDevice(&current);
      if (current != device_)
      {
        cudaSetDevice(device_);
      }
      cudaFree(data_);
      MemoryLedger::remove(device_, capacity_ * sizeof(T));
      if (current != device_)
      {
        cudaSetDevice(current);
      }
    }
    data_ = nullptr;
    size_ = capacity_ = 0;
  }

private:
  void swap(GPUBuffer& o) noexcept
  {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    std::swap(device_, o.device_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
  int device_ = 0;
};
}
