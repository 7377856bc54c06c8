// GPU-only measurements of linkgi-bench: the RGB bounce gather against cuSPARSE.
#pragma once

#include "linkgi/Solver.h"

namespace linkgi::bench
{
struct GatherBenchmark
{
  std::size_t rows = 0, nonZeros = 0;
  double usefulBytes = 0;       ///< matrix + x read once + y written once
  double msGather = 0;          ///< our RGB gather y = W x (median)
  double msBounce = 0;          ///< one fused bounce (gather + next radiance)
  double msCusparse = 0;        ///< three cusparseSpMV calls, one per channel (median)
  double maxRelativeDifference = 0; ///< between our y and cuSPARSE's
};

/// Links `scene` on the first GPU and times the gathers over its transport matrix.
GatherBenchmark benchmarkGather(const Scene& scene, const SolverOptions& options, int repeat);
}
