// Sparse matrices in CSR form: the transport matrices every method gathers through.
#pragma once

#include "linkgi/Scene.h"
#include "shared/NoFillVector.h"

#include <cstdint>
#include <vector>

namespace linkgi
{
/// Rows of a CSR matrix as the gather reads them: row r is entries [rowOffsets[r],
/// rowOffsets[r + 1]) counted from `firstEntry`, which columns[0] / weights[0] hold (0 for a
/// whole matrix; a slice of a larger one starts further on).
struct CsrRows
{
  const Offset* rowOffsets = nullptr; ///< rows + 1
  const Index* columns = nullptr;
  const float* weights = nullptr;
  std::size_t rows = 0;
  Offset firstEntry = 0;
};

/// Sparse matrix in CSR form; row = receiving element. Entry offsets are 64-bit (Offset).
struct SparseMatrix
{
  std::vector<Offset> rowOffsets; ///< rows + 1
  /// Not zero-filled on resize(): the link compression writes every entry, in parallel.
  NoFillVector<Index> columns;
  NoFillVector<float> weights;
  std::size_t rows() const { return rowOffsets.empty() ? 0 : rowOffsets.size() - 1; }
  std::size_t nonZeros() const { return columns.size(); }
  std::size_t bytes() const
  {
    return rowOffsets.size() * sizeof(Offset) + columns.size() * sizeof(Index) +
      weights.size() * sizeof(float);
  }
  CsrRows view() const { return { rowOffsets.data(), columns.data(), weights.data(), rows(), 0 }; }
};

/// offsets[0] = first, offsets[i + 1] = offsets[i] + counts[i]: row offsets from per-row
/// entry counts, in 64 bits (the sum passes 2^32 on large meshes). offsets gets counts + 1.
void exclusiveOffsets(const std::vector<Index>& counts, Offset first, std::vector<Offset>& offsets);
}
