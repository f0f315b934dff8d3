// RoundTotals: what a job's recorded rounds add up to at a checkpoint. A job resumed from a
// checkpoint (the master's RunningJob, `radfarm render --db`) starts from these totals, and `fetch`
// reports them, so the stopping rules see the same figures as in an uninterrupted solve.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "core/solve_stats.h"
#include "store/job_store.h"

namespace radfarm::store {

struct RoundTotals {
  uint32_t rounds = 0;  // rows summed
  uint64_t rays = 0;
  uint64_t escaped_rays = 0;
  uint64_t back_rays = 0;
  double seconds = 0;  // summed round durations
  // The unshot fraction after the last round summed; nullopt when none was.
  std::optional<double> unshot_fraction;

  // What a resumed solve has spent (solve/solve_state.h).
  SolveTotals solve_totals() const { return {rays, escaped_rays, back_rays, seconds}; }
};

// Sums the rows of `rounds` up to and including round `round`. `rounds` is in ListRounds' order
// (by round); summing stops at the first row past `round`, so rows recorded after the checkpoint
// (a round recorded between checkpoints) are left out. Adds in row order: the same bits every time.
RoundTotals TotalsUpToRound(std::span<const RoundRecord> rounds, uint32_t round);

}  // namespace radfarm::store
