// The RayTracer interface on one GPU (for tools, tests and checks of a result; the solver's
// CUDA path keeps rays and hits on the device instead).
#include "cuda/DeviceBvh.h"
#include "cuda/Kernels.h"

#include "cuda/Cuda.h"

#include <mutex>

namespace linkgi::cuda
{
namespace
{
/// Traces through a BVH on one GPU, on one stream of it: the rays are copied there and the
/// results back.
class DeviceBvhTracer : public RayTracer
{
public:
  DeviceBvhTracer(int device, cudaStream_t stream, const DeviceBvh* bvh) : device(device), stream(stream), bvh(bvh) {}

  const char* name() const override { return "cuda-lbvh"; }

  void build(const std::vector<Vec3f>&, const std::vector<Triangle>&) override
  {
    throw Error("This ray tracer traces the BVH its backend builds; it builds none.");
  }

  void refit(const std::vector<Vec3f>&) override
  {
    throw Error("This ray tracer traces the BVH its backend builds; it refits none.");
  }

  void trace(const Ray* r, Hit* h, std::size_t count) const override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    rays.upload(r, count, stream);
    hits.resize(count);
    traceRays(bvh->view(), rays.data(), hits.data(), count, stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    hits.download(h, count);
  }

  void occluded(const Ray* r, std::uint8_t* o, std::size_t count) const override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    rays.upload(r, count, stream);
    flags.resize(count);
    occludedRays(bvh->view(), rays.data(), flags.data(), count, stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    flags.download(o, count);
  }

protected:
  int device;
  cudaStream_t stream;
  const DeviceBvh* bvh;
  mutable std::mutex mutex;

private:
  mutable GPUBuffer<Ray> rays;
  mutable GPUBuffer<Hit> hits;
  mutable GPUBuffer<std::uint8_t> flags;
};

cudaStream_t newStream(int device)
{
  LINKGI_CUDA_CHECK(cudaSetDevice(device));
  cudaStream_t stream = nullptr;
  LINKGI_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  return stream;
}

/// A DeviceBvhTracer over a BVH and a stream of its own.
class CudaRayTracer final : public DeviceBvhTracer
{
public:
  explicit CudaRayTracer(int device) : DeviceBvhTracer(device, newStream(device), &own) {}
  ~CudaRayTracer() override
  {
    cudaSetDevice(device);
    cudaStreamDestroy(stream);
  }

  void build(const std::vector<Vec3f>& p, const std::vector<Triangle>& t) override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    positions.upload(p, stream);
    triangles.upload(t, stream);
    own.build(positions.data(), Index(p.size()), triangles.data(), Index(t.size()), stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  }

  void refit(const std::vector<Vec3f>& p) override
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (p.size() != positions.size())
    {
      throw Error("Refit needs a previous build with the same number of vertices.");
    }
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    positions.upload(p, stream);
    own.refit(positions.data(), triangles.data(), stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  }

private:
  GPUBuffer<Vec3f> positions;
  GPUBuffer<Triangle> triangles;
  DeviceBvh own;
};
}

std::unique_ptr<RayTracer> createRayTracer(int device)
{
  return std::make_unique<CudaRayTracer>(device);
}

std::unique_ptr<RayTracer> traceThrough(const DeviceBvh& bvh, int device, cudaStream_t stream)
{
  return std::make_unique<DeviceBvhTracer>(device, stream, &bvh);
}
}
