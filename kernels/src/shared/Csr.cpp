#include "shared/Csr.h"

namespace linkgi
{
void exclusiveOffsets(const std::vector<Index>& counts, Offset first, std::vector<Offset>& offsets)
{
  offsets.resize(counts.size() + 1);
  offsets[0] = first;
  for (std::size_t i = 0; i < counts.size(); ++i)
  {
    offsets[i + 1] = offsets[i] + counts[i]; // Offset + Index: no 32-bit wrap
  }
}
}
