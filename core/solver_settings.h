// Settings of the progressive-refinement solver; every field has a working default.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace radfarm {

enum class SamplerKind {
  kGrid,    // the seed paper's method: a fixed hemisphere grid from the patch centre
  kRandom,  // independent uniform origins and cosine-weighted directions
  kSobol,   // Sobol points over origin and direction, randomised per shot
};

std::string_view SamplerName(SamplerKind kind);
// Parses "grid", "random" or "sobol"; returns false for anything else.
bool ParseSamplerName(std::string_view name, SamplerKind* kind);

inline constexpr uint64_t kAutoShotRaysPerPatch = 1024;
// With the final gather on, the shooting only has to get the light that bounced roughly right: the
// gather averages its noise over every patch a gathering patch sees (docs/BENCHMARKS-adaptive.md).
inline constexpr uint64_t kAutoShotRaysPerPatchBeforeGather = 384;
// Gather rays per patch of a job that does not say (`gather_rays`; job/job.h). The solver's own
// default is 0, plain progressive refinement, which the core tests pin down.
inline constexpr uint32_t kDefaultGatherRays = 2048;
inline constexpr uint32_t kMaxGatherRays = 1u << 20;
// SolverSettings::threads at most: a job file's range, checked again when a bundle is decoded.
inline constexpr uint32_t kMaxSolverThreads = 65536;
inline constexpr uint64_t kMinAutoShotRays = 1 << 16;

// SolverSettings::overrelaxation lies in [kMinOverrelaxation, kMaxOverrelaxation): below 1 is
// under-relaxation, from 2 on nothing converges (rounds of many shooters diverge well before).
inline constexpr double kMinOverrelaxation = 1;
inline constexpr double kMaxOverrelaxation = 2;
// False for NaN.
constexpr bool IsValidOverrelaxation(double omega) {
  return omega >= kMinOverrelaxation && omega < kMaxOverrelaxation;
}

struct SolverSettings {
  SamplerKind sampler = SamplerKind::kSobol;
  uint64_t seed = 1;
  // Stop when the unshot power falls below this fraction of the emitted power.
  double tolerance = 1e-3;
  // Stop after this many rays (0: no limit) or this many seconds (0: no limit).
  uint64_t max_rays = 0;
  double max_seconds = 0;
  // Rays spent on shooting power equal to the scene's total emitted power: a shooter shooting
  // power P (omega |unshot|) gets shot_rays * P / emitted rays (at least min_shooter_rays). 0 picks
  // kAutoShotRaysPerPatch rays per patch (at least kMinAutoShotRays): accuracy per patch then
  // stays about the same whatever the mesh size.
  uint64_t shot_rays = 0;
  // 1 by default: then no ray carries more than emitted / shot_rays power and none less than half
  // of that, except the single ray of a shooter too weak for more (a higher floor spends most of a
  // late round's rays on patches that hardly matter).
  uint32_t min_shooter_rays = 1;
  // Upper bound on shooters per round (0: every patch with unshot power).
  uint32_t shooters_per_round = 0;
  // Over-relaxation factor omega of Southwell's method, in [1, 2): a shooter shoots omega times
  // its unshot radiosity and keeps (1 - omega) times it, negative above 1 (shot later as negative
  // light). 1: plain progressive refinement, the best measured (docs/SOLVER.md; the rows are in
  // docs/BENCHMARKS-adaptive.md).
  double overrelaxation = 1.0;
  // Grid sampler: angular step of the hemisphere grid in degrees.
  double grid_step_degrees = 1.0;
  // Final gather (0: off). When on, the solve starts from the direct light computed at each patch
  // (core/direct_light.h) instead of shooting the emitters' light, and once the unshot power is
  // below the tolerance one last round casts this many rays from every reflecting patch and sets
  // B = E + rho * (direct + the mean over those rays of the hit patch's radiosity less its
  // emission). Ignored by the grid sampler (whose shot size is fixed) and by a refining solve
  // before its restart point (RefinementSchedule::SolverSettingsNow).
  uint32_t gather_rays = 0;
  // Worker threads (0: all cores). Never changes the result.
  uint32_t threads = 0;
};

// Whether the solve gathers: gather_rays > 0 and a sampler whose shots can be any size.
constexpr bool GatherOn(const SolverSettings& settings) {
  return settings.gather_rays > 0 && settings.sampler != SamplerKind::kGrid;
}

// settings.shot_rays, or the automatic count for a scene of `patches` patches when it is 0.
constexpr uint64_t ResolvedShotRays(const SolverSettings& settings, uint64_t patches) {
  if (settings.shot_rays > 0) return settings.shot_rays;
  const uint64_t per_patch =
      GatherOn(settings) ? kAutoShotRaysPerPatchBeforeGather : kAutoShotRaysPerPatch;
  const uint64_t automatic = per_patch * patches;
  return automatic > kMinAutoShotRays ? automatic : kMinAutoShotRays;
}

// The rays a part of a budgeted solve may cast (0: no budget): a `share`-th of max_rays, and of
// max_seconds at `rays_per_second` (a rate fixed in the code, so the plan is the same on every
// machine), the smaller of the two, at least one. The direct-light start (StartRayAllowance) and
// the display (DisplayRayAllowance) each get a quarter.
uint64_t BudgetShare(const SolverSettings& settings, uint64_t share, double rays_per_second);

}  // namespace radfarm
