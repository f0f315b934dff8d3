// Sections 3 and 4 of the report: the seed paper's workload (its room, 20 shots of a 1 degree
// hemisphere grid, one shooter per round) timed on this machine, and the default sampler given
// about the same wall time on the same room. Every time compared here is measured alternately with
// the time it is compared with, so both see the same load on a shared machine.
#pragma once

#include <cstdint>
#include <vector>

#include "bench/bench_scene.h"
#include "bench/sweep.h"

namespace radfarm::bench {

// The seed paper's figure: 187 s for this workload on a Pentium 4.
inline constexpr double kSeedPaperSeconds = 187;
inline constexpr uint32_t kSeedShots = 20;

// A budget of the default sampler tried against the seed workload.
struct EqualTimeCandidate {
  SweepPoint point;
  double seed_seconds = 0;  // the seed workload's median, timed alternately with this one
};

struct SeedWorkload {
  SweepPoint seed;                // all threads; seconds: median of the repetitions
  double one_thread_seconds = 0;  // median, SolverSettings::threads = 1, alternating with `seed`
  int repetitions = 0;
  int match_repetitions = 0;
  size_t patches = 0;
  // The default settings as they are (automatic shot_rays), then with shot_rays halved: ascending
  // budget, so the defaults come last.
  std::vector<EqualTimeCandidate> tried;
  // Median of every seed-workload run made alongside the candidates.
  double seed_seconds_alongside = 0;
  // True when no budget fits in the seed's time: min_shooter_rays sets a floor on the default's
  // time, and the match is the largest budget as fast as the fastest.
  bool at_floor = false;
  EqualTimeCandidate equal_time;  // the one of `tried` matched to the seed's time
  double error_ratio = 0;         // seed.error / equal_time.error
  double error_ratio_lit = 0;     // seed.error_lit / equal_time.error_lit
};

SolverSettings SeedSettings();

// `reference` must be the seed room's. Times the seed workload (median of `repetitions`,
// alternating with a one-thread run), then halves the default sampler's shot_rays down from its
// automatic value until a solve (median of `match_repetitions`, alternating with the seed workload)
// takes about as long as the seed workload, and scores both.
SeedWorkload RunSeedWorkload(const BenchScene& room, const Reference& reference, int repetitions,
                             int match_repetitions);

}  // namespace radfarm::bench
