// The bounce gather against cuSPARSE on the same matrix, in the same run: our one-pass RGB
// gather (16-byte vector loads) versus three scalar cusparseSpMV calls.
#include "BenchCuda.h"

#include "methods/links/cuda/CudaEngine.h"
#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"

#include "methods/links/Links.h"
#include "scene/Topology.h"

#include <cusparse.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace linkgi::bench
{
namespace
{
using namespace cuda;

void checkSparse(cusparseStatus_t status, const char* what)
{
  if (status != CUSPARSE_STATUS_SUCCESS)
  {
    throw Error(std::string("cuSPARSE failed in ") + what + ": " + cusparseGetErrorString(status));
  }
}

/// Median of `repeat` timings of f() on `stream`, each bracketed by events.
template <typename F>
double medianMs(int repeat, cudaStream_t stream, F&& f)
{
  cudaEvent_t a, b;
  LINKGI_CUDA_CHECK(cudaEventCreate(&a));
  LINKGI_CUDA_CHECK(cudaEventCreate(&b));
  f(); // warm-up
  std::vector<double> ms;
  for (int r = 0; r < repeat; ++r)
  {
    LINKGI_CUDA_CHECK(cudaEventRecord(a, stream));
    f();
    LINKGI_CUDA_CHECK(cudaEventRecord(b, stream));
    LINKGI_CUDA_CHECK(cudaEventSynchronize(b));
    float t = 0.f;
    LINKGI_CUDA_CHECK(cudaEventElapsedTime(&t, a, b));
    ms.push_back(t);
  }
  cudaEventDestroy(a);
  cudaEventDestroy(b);
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

struct Cusparse
{
  cusparseHandle_t handle = nullptr;
  cusparseSpMatDescr_t matrix = nullptr;
  cusparseDnVecDescr_t x[3] = {}, y[3] = {};
  GPUBuffer<unsigned char> buffer;

  Cusparse(const CsrView& w, const Index* rowOffsets, GPUBuffer<float>* xs, GPUBuffer<float>* ys,
    cudaStream_t stream)
  {
    checkSparse(cusparseCreate(&handle), "cusparseCreate");
    checkSparse(cusparseSetStream(handle, stream), "cusparseSetStream");
    checkSparse(cusparseCreateCsr(&matrix, w.rows, w.rows, w.nonZeros,
                  const_cast<Index*>(rowOffsets), const_cast<Index*>(w.columns),
                  const_cast<float*>(w.weights), CUSPARSE_INDEX_32I, CUSPARSE_INDEX_32I,
                  CUSPARSE_INDEX_BASE_ZERO, CUDA_R_32F),
      "cusparseCreateCsr");
    for (int c = 0; c < 3; ++c)
    {
      checkSparse(cusparseCreateDnVec(&x[c], w.rows, xs[c].data(), CUDA_R_32F), "cusparseCreateDnVec");
      checkSparse(cusparseCreateDnVec(&y[c], w.rows, ys[c].data(), CUDA_R_32F), "cusparseCreateDnVec");
    }
    const float one = 1.f, zero = 0.f;
    std::size_t bytes = 0;
    checkSparse(cusparseSpMV_bufferSize(handle, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, matrix,
                  x[0], &zero, y[0], CUDA_R_32F, CUSPARSE_SPMV_ALG_DEFAULT, &bytes),
      "cusparseSpMV_bufferSize");
    buffer.resize(std::max<std::size_t>(bytes, 1));
  }
  ~Cusparse()
  {
    for (int c = 0; c < 3; ++c)
    {
      cusparseDestroyDnVec(x[c]);
      cusparseDestroyDnVec(y[c]);
    }
    cusparseDestroySpMat(matrix);
    cusparseDestroy(handle);
  }
  void run()
  {
    const float one = 1.f, zero = 0.f;
    for (int c = 0; c < 3; ++c)
    {
      checkSparse(cusparseSpMV(handle, CUSPARSE_OPERATION_NON_TRANSPOSE, &one, matrix, x[c], &zero,
                    y[c], CUDA_R_32F, CUSPARSE_SPMV_ALG_DEFAULT, buffer.data()),
        "cusparseSpMV");
    }
  }
};
}

GatherBenchmark benchmarkGather(const Scene& input, const SolverOptions& options, int repeat)
{
  Scene scene = input;
  validateScene(scene);
  Engine gpu(1);
  Solution solution;
  SolverStats stats;
  for (std::size_t stage : { links::kGeometryStage, links::kLinkStage, links::kLightLinkStage, links::kBounceStage })
  {
    gpu.run(stage, engine::StageContext(scene, options, engine::kEverything, {}, solution, stats, "bench"));
  }
  const CsrView w = gpu.transport();
  LINKGI_CUDA_CHECK(cudaSetDevice(0));
  cudaStream_t stream;
  LINKGI_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));

  // Random radiance in [0,1): the same values as one RGB vector and as three channels.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  std::vector<Rgba> x(w.rows);
  std::vector<float> channel[3];
  for (Rgba& v : x)
  {
    v = { uniform(rng), uniform(rng), uniform(rng), 0.f };
    channel[0].push_back(v.r);
    channel[1].push_back(v.g);
    channel[2].push_back(v.b);
  }
  GPUBuffer<Rgba> dx, dy, next, fixed;
  dx.upload(x, stream);
  dy.resize(w.rows);
  next.resize(w.rows);
  fixed.upload(x, stream);
  GPUBuffer<float> xs[3], ys[3];
  for (int c = 0; c < 3; ++c)
  {
    xs[c].upload(channel[c], stream);
    ys[c].resize(w.rows);
  }
  GPUBuffer<Vec3f> albedo(scene.vertexCount()), direct(w.rows);
  albedo.fillZero(stream);
  direct.fillZero(stream);
  BounceParams b;
  b.elements = w.rows;
  b.vertexCount = Index(scene.vertexCount());
  b.albedo = albedo.data();
  b.direct = direct.data();

  GatherBenchmark out;
  out.rows = w.rows;
  out.nonZeros = w.nonZeros;
  // Matrix (entries, row starts and counts), x read once, y written once.
  out.usefulBytes = double(w.nonZeros) * 8.0 + w.rows * 8.0 + 2.0 * w.rows * sizeof(Rgba);
  out.msGather = medianMs(repeat, stream, [&] { gatherRgb(w, dx.data(), dy.data(), stream); });
  out.msBounce = medianMs(repeat, stream,
    [&] { bounce(w, b, fixed.data(), dx.data(), dy.data(), next.data(), stream); });
  gatherRgb(w, dx.data(), dy.data(), stream);
  // One batch on one GPU: the row starts plus the total are CSR offsets. cuSPARSE gets them
  // as 32-bit offsets, which holds below 2^32 links.
  if (w.nonZeros >= kInvalidIndex)
  {
    throw Error("The gather benchmark compares with cuSPARSE below 2^32 links only.");
  }
  std::vector<Offset> starts(w.rows);
  std::vector<Index> offsets(w.rows + 1), counts(w.rows);
  LINKGI_CUDA_CHECK(cudaMemcpy(starts.data(), w.rowStarts, w.rows * sizeof(Offset), cudaMemcpyDeviceToHost));
  LINKGI_CUDA_CHECK(cudaMemcpy(counts.data(), w.rowCounts, w.rows * sizeof(Index), cudaMemcpyDeviceToHost));
  std::copy(starts.begin(), starts.end(), offsets.begin());
  offsets[w.rows] = Index(w.nonZeros);
  for (Index r = 0; r < w.rows; ++r)
  {
    if (offsets[r] + counts[r] != offsets[r + 1])
    {
      throw Error("The transport matrix's rows are not in order; cuSPARSE needs plain CSR.");
    }
  }
  GPUBuffer<Index> rowOffsets;
  rowOffsets.upload(offsets, stream);
  Cusparse sparse(w, rowOffsets.data(), xs, ys, stream);
  out.msCusparse = medianMs(repeat, stream, [&] { sparse.run(); });

  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  const std::vector<Rgba> ours = dy.download();
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const std::vector<float> theirs = ys[c].download();
    for (std::size_t i = 0; i < theirs.size(); ++i)
    {
      const float mine = c == 0 ? ours[i].r : c == 1 ? ours[i].g : ours[i].b;
      worst = std::max(worst, std::fabs(double(mine) - theirs[i]) / std::max(1e-6, std::fabs(double(theirs[i]))));
    }
  }
  out.maxRelativeDifference = worst;
  cudaStreamDestroy(stream);
  return out;
}
}
