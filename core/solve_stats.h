// Figures of a finished (or stopped) solve, written to stats.json, and the running totals they
// are made from.
#pragma once

#include <cstdint>
#include <string>

#include "core/progressive_solver.h"

namespace radfarm {

// What a solve has spent: summed over its rounds (a resumed solve starts from a checkpoint's).
struct SolveTotals {
  uint64_t rays = 0;
  uint64_t escaped_rays = 0;   // rays that left the scene without a hit
  uint64_t backface_hits = 0;  // rays that hit the back of a patch (absorbed)
  double seconds = 0;
};

struct SolveStats {
  uint64_t rays = 0;
  // Shadow rays of the direct light the solve started from (ProgressiveSolver::start_rays): with
  // `rays`, what the ray budget counts. 0 where unknown (a solution fetched from the master).
  uint64_t start_rays = 0;
  // Seconds from the solve's start to its first round: the direct-light start and the solver's
  // set-up (0 where unknown: a solution fetched from the master).
  double start_seconds = 0;
  uint64_t rounds = 0;
  double seconds = 0;
  double rays_per_second = 0;
  uint64_t patches = 0;
  double unshot_fraction = 0;  // unshot power / emitted power when the solve stopped
  uint64_t escaped_rays = 0;   // rays that left the scene without a hit
  uint64_t backface_hits = 0;  // rays that hit the back of a patch (absorbed)
  uint32_t threads = 0;
  uint64_t seed = 0;
  std::string sampler;
  std::string stop_reason;    // "converged", "ray budget", "time budget"
  double emitted_power = 0;   // sum of area * emission over patches (channel sum)
  double absorbed_power = 0;  // channel sums, so emitted = absorbed + unshot + escaped
  double escaped_power = 0;
};

// The figures that follow from the totals and the energy account: rays, seconds, escaped and
// back-face counts, rays per second and the three powers. The caller fills in the rest.
SolveStats StatsOf(const SolveTotals& totals, const EnergyAccount& energy);

}  // namespace radfarm
