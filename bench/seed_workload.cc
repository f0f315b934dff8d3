#include "bench/seed_workload.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/solver_settings.h"

namespace radfarm::bench {

SolverSettings SeedSettings() {
  SolverSettings s;
  s.sampler = SamplerKind::kGrid;
  s.grid_step_degrees = 1;
  s.shooters_per_round = 1;
  // Solve checks the budget between rounds and every round is one 90 x 360 shot, so it stops after
  // exactly 20 rounds.
  s.max_rays = uint64_t{kSeedShots} * 90 * 360;
  return s;
}

SeedWorkload RunSeedWorkload(const BenchScene& room, const Reference& reference, int repetitions,
                             int match_repetitions) {
  SeedWorkload out;
  out.repetitions = repetitions;
  out.match_repetitions = match_repetitions;
  out.patches = room.patches().patches.size();
  out.seed =
      RunPoint(room, SeedSettings(), "1°, 20 shots, 1 shooter per round", reference, repetitions);
  PrintPoint(room.name, out.seed);
  if (out.seed.rounds != kSeedShots) {
    std::fprintf(stderr, "solver_bench: the seed workload ran %llu rounds, not %u\n",
                 static_cast<unsigned long long>(out.seed.rounds), kSeedShots);
  }
  SolverSettings one = SeedSettings();
  one.threads = 1;
  out.one_thread_seconds = RunPoint(room, one, "", reference, repetitions).seconds;
  std::printf("%s: seed workload on 1 thread: %.3f s (median)\n", room.name.c_str(),
              out.one_thread_seconds);

  const SolverSettings defaults;
  out.default_auto =
      RunPoint(room, defaults, "defaults (shot_rays automatic)", reference, match_repetitions);
  PrintPoint(room.name, out.default_auto);
  // Halve shot_rays from its automatic value (as ProgressiveSolver resolves it) until a solve takes
  // about the seed's time (at most kTimeSlack longer: single timings of a fifth of a second jitter
  // by more than that), or until halving stops saving rays: min_shooter_rays then sets a floor of
  // rays per round, and smaller budgets only add error.
  constexpr double kTimeSlack = 1.1;
  constexpr double kFloorRayRatio = 0.9;
  const double limit = kTimeSlack * out.seed.seconds;
  out.tried.push_back(out.default_auto);
  uint64_t shot_rays =
      std::max(kMinAutoShotRays, kAutoShotRaysPerPatch * room.patches().patches.size());
  while (out.tried.front().seconds > limit && shot_rays / 2 >= 1024) {
    shot_rays /= 2;
    SolverSettings s = defaults;
    s.shot_rays = shot_rays;
    const uint64_t previous_rays = out.tried.front().rays;
    out.tried.insert(out.tried.begin(), RunPoint(room, s, "shot_rays " + std::to_string(shot_rays),
                                                 reference, match_repetitions));
    PrintPoint(room.name, out.tried.front());
    if (double(out.tried.front().rays) > kFloorRayRatio * double(previous_rays)) break;
  }
  // The largest budget within the time; failing that, the first one at the floor.
  out.equal_time = out.tried.front();
  for (const SweepPoint& p : out.tried) {
    if (p.seconds <= limit) out.equal_time = p;
  }
  out.error_ratio = out.equal_time.error > 0 ? out.seed.error / out.equal_time.error : 0;
  out.error_ratio_lit =
      out.equal_time.error_lit > 0 ? out.seed.error_lit / out.equal_time.error_lit : 0;
  return out;
}

}  // namespace radfarm::bench
