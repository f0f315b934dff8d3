// What a solve needs in memory, estimated from its patch count before anything large is allocated,
// so a job too big for the machine is refused with the figures instead of killed by the kernel.
// The constants are measured peaks of `radfarm render` over a wide range of patch counts
// (docs/MEMORY.md) with some headroom; the farm master's peak per patch is below render's.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace radfarm {

// The program, the image buffers (512 x 512 x 4 samples) and the libraries.
inline constexpr uint64_t kSolveBaseBytes = uint64_t{96} << 20;
// Mesh, patch scene, solver state, ray caster and display mesh, per patch.
inline constexpr uint64_t kSolveBytesPerPatch = 1152;

uint64_t EstimatedSolveBytes(uint64_t patches);
// The most patches whose EstimatedSolveBytes fit in `memory_bytes`; nullopt when it is no more
// than the base (unknown, or too little for any: EstimatedSolveBytes against it refuses that).
std::optional<uint64_t> PatchesThatFit(uint64_t memory_bytes);

// This machine's physical memory (the default limit), 0 if unknown.
uint64_t PhysicalMemoryBytes();

// "1234 MB": whole mebibytes, rounded up.
std::string FormatMegabytes(uint64_t bytes);

}  // namespace radfarm
