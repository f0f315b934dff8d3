// What a re-bake (`radfarm render --from DIR`) needs of a previous render, kept in that render's
// output directory as `rebake.bin` (format below and in docs/USAGE.md): the solution per patch,
// the meshing it belongs to and the direct light it started from.
//
// rebake.bin, little-endian:
//   8 bytes   "RFREBAKE"
//   u32       version (1)
//   u32       patches n
//   u8        flags: 1 emitters in the direct start, 2 direct light stored, 4 start work stored
//   64 bytes  geometry hash: SHA-256, hex, of the patches' shapes, surfaces and materials
//   64 bytes  lamps hash: SHA-256, hex, of the same with the punctual lamps (whether the start
//             can be the previous one plus what the emission's change adds)
//   u32 u64 u8 u32   the start work: sections, seed, emitters, rays_per_light (zeros if none)
//   f64       the punctual lamps' power the start counted
//   n x 15 f64  per patch: radiosity, unshot, emission, reflectance, direct light (r, g, b each;
//               the direct light zeros when not stored)
// Values are the solve's exact bits, so a re-bake of the same inputs starts from the same bits.
#pragma once

#include <optional>
#include <string>

#include "base/result.h"
#include "core/direct_start.h"
#include "core/warm_start.h"
#include "solve/solve_state.h"

namespace radfarm {

inline constexpr const char* kPreviousSolveFile = "rebake.bin";

struct PreviousSolve {
  std::string geometry_hash;  // 64 hex digits
  std::string lamps_hash;     // 64 hex digits
  std::optional<StartWork> start_work;
  PreviousPatchValues values;
};

// The values a re-bake of `solution`, solved on `scene`, starts from.
PreviousPatchValues PreviousValuesOf(const PatchScene& scene, const SolveResult& solution);

// A re-bake's start (RefiningHooks::start) from `previous`, whose punctual lamps the caller found
// unchanged: the previous direct light plus that of the emission's change (core/delta_start.h),
// traced on `threads`; or the whole start traced again where the previous one is of another kind
// (none, or without the emitters where this one has them). `previous` must outlive it.
StartLightSource RebakeStart(const PreviousPatchValues& previous, unsigned threads);

// Writes `solve` to `path` atomically.
Status WritePreviousSolve(const std::string& path, const PreviousSolve& solve);
// Reads and checks a file WritePreviousSolve wrote: its size against its patch count, finite
// values, reflectance in [0, 1). Errors name `path`.
Result<PreviousSolve> ReadPreviousSolve(const std::string& path);

}  // namespace radfarm
