// The CUDA backend's link-entry offsets past 2^32 on small buffers: the 64-bit scan of
// per-row counts, the packing of rows at offsets above 2^32 and the gather over them. The
// kernels get pointers moved back by the offset base, so a 32-bit wrap anywhere would read or
// write outside the buffers (and compute-sanitizer would say so).
#include "CudaFixtures.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"
#include "cuda/Primitives.h"

#include <cstdint>

using namespace linkgi;
using namespace linkgi::cuda;

TEST(CudaOffsets, ScanOfEntryCountsSumsIn64Bits)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const std::vector<Index> counts = { 1u << 31, 1u << 31, 1u << 31, 5 };
  GPUBuffer<Index> in;
  GPUBuffer<Offset> out(counts.size());
  GPUBuffer<unsigned char> temp;
  in.upload(counts);
  exclusiveSum(in.data(), out.data(), counts.size(), temp, nullptr);
  const std::vector<Offset> offsets = out.download();
  EXPECT_EQ(offsets, (std::vector<Offset>{ 0, Offset(1) << 31, Offset(1) << 32, Offset(3) << 31 }));
}

TEST(CudaOffsets, PackingAndGatherUseOffsetsAbove4G)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  const Offset base = (Offset(1) << 32) + 5;
  // Two rows in a scratch of capacity 4: row 0 has 3 entries, row 1 has 2.
  const std::vector<Index> srcColumns = { 2, 0, 1, 9, 1, 2, 9, 9 };
  const std::vector<float> srcWeights = { 1.f, 2.f, 3.f, 9.f, 4.f, 5.f, 9.f, 9.f };
  GPUBuffer<Index> columns, counts, packedColumns(5), packedCounts(2);
  GPUBuffer<float> weights, packedWeights(5);
  GPUBuffer<Offset> offsets, packedStarts(2);
  columns.upload(srcColumns);
  weights.upload(srcWeights);
  counts.upload(std::vector<Index>{ 3, 2 });
  offsets.upload(std::vector<Offset>{ base, base + 3 });
  // Entry i of the matrix is packed[i - base]: the kernels add the offset back.
  const PackedRows to{ packedColumns.data() - base, packedWeights.data() - base, packedStarts.data(),
    packedCounts.data() };
  packRows(columns.data(), weights.data(), 4, counts.data(), offsets.data(), 2, to, nullptr);
  EXPECT_EQ(packedColumns.download(), (std::vector<Index>{ 2, 0, 1, 1, 2 }));
  EXPECT_EQ(packedWeights.download(), (std::vector<float>{ 1.f, 2.f, 3.f, 4.f, 5.f }));
  EXPECT_EQ(packedStarts.download(), (std::vector<Offset>{ base, base + 3 }));

  // The gather over those rows, as elements 1 and 2 of a 3-element vector.
  const std::vector<Rgba> x = { { 1, 2, 3, 0 }, { 4, 5, 6, 0 }, { 7, 8, 9, 0 } };
  GPUBuffer<Rgba> dx, dy(3);
  dx.upload(x);
  dy.fillZero();
  CsrView m;
  m.rowStarts = packedStarts.data();
  m.rowCounts = packedCounts.data();
  m.columns = packedColumns.data() - base;
  m.weights = packedWeights.data() - base;
  m.rows = 2;
  m.firstElement = 1;
  m.nonZeros = 5;
  gatherRgb(m, dx.data(), dy.data(), nullptr);
  const std::vector<Rgba> y = dy.download();
  EXPECT_FLOAT_EQ(y[0].r, 0.f);
  EXPECT_FLOAT_EQ(y[1].r, 1.f * 7 + 2.f * 1 + 3.f * 4);
  EXPECT_FLOAT_EQ(y[1].b, 1.f * 9 + 2.f * 3 + 3.f * 6);
  EXPECT_FLOAT_EQ(y[2].g, 4.f * 5 + 5.f * 8);
}
