// The RayTracer interface on one GPU (for tools and tests; the solver's CUDA path keeps
// rays and hits on the device instead).
#include "cuda/DeviceBvh.h"
#include "cuda/Kernels.h"

#include "cuda/Cuda.h"

#include <mutex>

namespace linkgi::cuda
{
namespace
{
class CudaRayTracer final : public RayTracer
{
public:
  explicit CudaRayTracer(int device) : device(device)
  {
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    LINKGI_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  }
  ~CudaRayTracer() override
  {
    cudaSetDevice(device);
    cudaStreamDestroy(stream);
  }

  const char* name() const override { return "cuda-lbvh"; }

  void build(const std::vector<Vec3f>& p, const std::vector<Triangle>& t) override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    positions.upload(p, stream);
    triangles.upload(t, stream);
    bvh.build(positions.data(), Index(p.size()), triangles.data(), Index(t.size()), stream);
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
    bvh.refit(positions.data(), triangles.data(), stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  }

  void trace(const Ray* r, Hit* h, std::size_t count) const override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    rays.upload(r, count, stream);
    hits.resize(count);
    traceRays(bvh.view(), rays.data(), hits.data(), count, stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    hits.download(h, count);
  }

  void occluded(const Ray* r, std::uint8_t* o, std::size_t count) const override
  {
    std::lock_guard<std::mutex> lock(mutex);
    LINKGI_CUDA_CHECK(cudaSetDevice(device));
    rays.upload(r, count, stream);
    flags.resize(count);
    occludedRays(bvh.view(), rays.data(), flags.data(), count, stream);
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
    flags.download(o, count);
  }

private:
  int device;
  cudaStream_t stream = nullptr;
  GPUBuffer<Vec3f> positions;
  GPUBuffer<Triangle> triangles;
  DeviceBvh bvh;
  mutable std::mutex mutex;
  mutable GPUBuffer<Ray> rays;
  mutable GPUBuffer<Hit> hits;
  mutable GPUBuffer<std::uint8_t> flags;
};
}

std::unique_ptr<RayTracer> createRayTracer(int device)
{
  return std::make_unique<CudaRayTracer>(device);
}
}
