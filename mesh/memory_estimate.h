// What a solve needs in memory, estimated from its patch count before anything large is allocated,
// so a job too big for the machine is refused with the figures instead of killed by the kernel.
// The constants are measured peaks (`radfarm render`, Cornell box from 3,849 to 860,235 patches:
// docs/MEMORY.md) with some headroom; the farm master's peak per patch is below render's.
#pragma once

#include <cstdint>
#include <string>

namespace radfarm {

// The program, the image buffers (512 x 512 x 4 samples) and the libraries.
inline constexpr uint64_t kSolveBaseBytes = uint64_t{96} << 20;
// Mesh, patch scene, solver state, ray caster and display mesh, per patch.
inline constexpr uint64_t kSolveBytesPerPatch = 1152;

uint64_t EstimatedSolveBytes(uint64_t patches);

// This machine's physical memory (the default limit), 0 if unknown.
uint64_t PhysicalMemoryBytes();

// "1234 MB": whole mebibytes, rounded up.
std::string FormatMegabytes(uint64_t bytes);

}  // namespace radfarm
