#include "mesh/memory_estimate.h"

#include <unistd.h>

namespace radfarm {

uint64_t EstimatedSolveBytes(uint64_t patches) {
  return kSolveBaseBytes + kSolveBytesPerPatch * patches;
}

std::optional<uint64_t> PatchesThatFit(uint64_t memory_bytes) {
  if (memory_bytes <= kSolveBaseBytes) return std::nullopt;
  return (memory_bytes - kSolveBaseBytes) / kSolveBytesPerPatch;
}

uint64_t PhysicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(page_size);
}

std::string FormatMegabytes(uint64_t bytes) {
  constexpr uint64_t kMiB = uint64_t{1} << 20;
  return std::to_string(bytes / kMiB + (bytes % kMiB != 0)) + " MB";
}

}  // namespace radfarm
