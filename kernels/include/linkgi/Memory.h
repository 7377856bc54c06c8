// Memory: what an update is estimated to need, what the machine can give, and the peak a
// process reached. The orchestrator compares the first two before it links anything
// (engine/MemoryBudget.h), so a mesh too large for the machine gets a clear error instead of
// the operating system's out-of-memory killer.
#pragma once

#include "linkgi/Error.h"
#include "linkgi/Scene.h"

#include <cstdint>
#include <string>

namespace linkgi
{
/// Bytes an update allocates at its peak, on the host and on the GPU(s) together.
struct MemoryEstimate
{
  std::uint64_t hostBytes = 0;
  std::uint64_t deviceBytes = 0;
};

/// The sizes an estimate depends on (a method's estimate is a function of these and the
/// options alone, so the orchestrator can ask what a smaller mesh would need).
struct MemoryShape
{
  std::uint64_t vertices = 0, triangles = 0;
  std::uint64_t texels = 1; ///< environment texels (1 for a constant colour)
  /// What the method's CPU backend measured per element on this geometry by sampling it
  /// (MethodBackend::sampleMemory; the link method: links per row), 0 where nothing was
  /// measured and the estimate takes its bound.
  double sampledPerElement = 0.0;
  static MemoryShape of(const Scene& scene);
};

/// An update refused by the memory budget. verticesThatFit(): the most vertices that the
/// same update would fit at the same options (0 when none), e.g. for a proxy of that size.
/// what() is the estimate and what would fit (`detail`), then that the previous result is
/// kept; a caller that lights the surface another way reports detail() alone.
class OutOfMemoryBudget : public Error
{
public:
  OutOfMemoryBudget(const std::string& detail, std::uint64_t verticesThatFit)
    : Error(detail + " The previous result is kept."), reason(detail), fit(verticesThatFit)
  {
  }
  std::uint64_t verticesThatFit() const { return fit; }
  const std::string& detail() const { return reason; }

private:
  std::string reason;
  std::uint64_t fit;
};

/// The host memory the operating system can give this process now without swapping:
/// /proc/meminfo's MemAvailable. 0 where it cannot be read (not Linux).
std::uint64_t availableHostBytes();

/// Makes availableHostBytes() return `bytes` from now on (0: read the system again), for
/// tests of what updates do when the machine's free memory changes between them.
void overrideAvailableHostBytes(std::uint64_t bytes);

/// The budget an update runs under: `requested` bytes when it is not 0, otherwise what is
/// available less a margin for the rest of the process (the renderer, ParaView): a tenth
/// of it, at least 512 MiB. No limit (UINT64_MAX) where the available memory is unknown.
std::uint64_t hostMemoryBudget(std::uint64_t requested);

/// Hands the pages of freed heap memory back to the operating system (glibc's malloc_trim;
/// nothing elsewhere). Freed blocks in the middle of the heap otherwise stay resident, so a
/// stage that frees as it copies would not lower the process's peak.
void returnFreedMemory();

/// "1.50 GiB", "12.0 MiB", "640 B".
std::string formatBytes(std::uint64_t bytes);

/// This process's peak resident set (VmHWM) and current one (VmRSS) in bytes, 0 where
/// unknown. resetPeakResident() makes the peak the current size (Linux 4.0+), so the peak of
/// one piece of work can be read; false where the kernel does not allow it.
std::uint64_t peakResidentBytes();
std::uint64_t residentBytes();
bool resetPeakResident();
}
