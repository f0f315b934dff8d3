#include "bench/seed_workload.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/stopwatch.h"
#include "bench/timed_solve.h"
#include "core/solver_settings.h"

namespace radfarm::bench {
namespace {

// A solve is "about as long" as the seed workload when at most this much longer: timings of a
// fifth of a second on a shared machine jitter by that much.
constexpr double kTimeSlack = 1.1;
// Halving shot_rays has reached min_shooter_rays' floor of rays per round when it saves less than
// this share of the rays; smaller budgets then only add error.
constexpr double kFloorRayRatio = 0.9;
constexpr uint64_t kSmallestShotRays = 1024;

// Times `settings` alternately with the seed workload; appends the seed's times to *seed_times.
EqualTimeCandidate TryBudget(const BenchScene& room, const SolverSettings& settings,
                             std::string budget, const Reference& reference, int repetitions,
                             std::vector<double>* seed_times) {
  const auto [seed, candidate] =
      RunTimedPair(room.patches(), SeedSettings(), settings, repetitions);
  seed_times->insert(seed_times->end(), seed.seconds.begin(), seed.seconds.end());
  EqualTimeCandidate out;
  out.point = ScorePoint(candidate, settings, std::move(budget), reference);
  out.seed_seconds = seed.median_seconds;
  PrintPoint(room.name, out.point);
  std::printf("%s:   (seed workload alongside: %.3f s)\n", room.name.c_str(), out.seed_seconds);
  return out;
}

}  // namespace

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
  SolverSettings one = SeedSettings();
  one.threads = 1;
  const auto [all_threads, one_thread] =
      RunTimedPair(room.patches(), SeedSettings(), one, repetitions);
  out.seed =
      ScorePoint(all_threads, SeedSettings(), "1°, 20 shots, 1 shooter per round", reference);
  out.one_thread_seconds = one_thread.median_seconds;
  PrintPoint(room.name, out.seed);
  std::printf("%s: seed workload on 1 thread: %.3f s (median)\n", room.name.c_str(),
              out.one_thread_seconds);
  if (out.seed.rounds != kSeedShots) {
    std::fprintf(stderr, "solver_bench: the seed workload ran %llu rounds, not %u\n",
                 static_cast<unsigned long long>(out.seed.rounds), kSeedShots);
  }

  // Halve shot_rays from its automatic value (as ProgressiveSolver resolves it) until a solve takes
  // about the seed's time, or until halving stops saving rays.
  const SolverSettings defaults;
  std::vector<double> seed_times;
  out.tried.push_back(TryBudget(room, defaults, "defaults (shot_rays automatic)", reference,
                                match_repetitions, &seed_times));
  uint64_t shot_rays = ResolvedShotRays(defaults, room.patches().patches.size());
  while (out.tried.front().point.seconds > kTimeSlack * Median(seed_times) &&
         shot_rays / 2 >= kSmallestShotRays) {
    shot_rays /= 2;
    SolverSettings s = defaults;
    s.shot_rays = shot_rays;
    const uint64_t previous_rays = out.tried.front().point.rays;
    out.tried.insert(out.tried.begin(), TryBudget(room, s, "shot_rays " + std::to_string(shot_rays),
                                                  reference, match_repetitions, &seed_times));
    if (double(out.tried.front().point.rays) > kFloorRayRatio * double(previous_rays)) break;
  }
  // The largest budget that takes about the seed's time, or, when none is that fast, about the
  // fastest budget's time.
  out.seed_seconds_alongside = Median(seed_times);
  double fastest = out.tried.front().point.seconds;
  for (const EqualTimeCandidate& c : out.tried) fastest = std::min(fastest, c.point.seconds);
  out.at_floor = fastest > kTimeSlack * out.seed_seconds_alongside;
  const double limit = kTimeSlack * std::max(out.seed_seconds_alongside, fastest);
  out.equal_time = out.tried.front();
  for (const EqualTimeCandidate& c : out.tried) {
    if (c.point.seconds <= limit) out.equal_time = c;
  }
  const SweepPoint& eq = out.equal_time.point;
  out.error_ratio = eq.error > 0 ? out.seed.error / eq.error : 0;
  out.error_ratio_lit = eq.error_lit > 0 ? out.seed.error_lit / eq.error_lit : 0;
  return out;
}

}  // namespace radfarm::bench
