// ProgressEstimator: how much of a solve is done and how long the rest will take, from the rounds
// seen so far. Pure arithmetic with no clock: the caller passes each round's rays and seconds, so
// tests drive it with made-up rounds; `radfarm render` and the farm master feed it the same way.
//
// The model. Work is rays, and the rays still to come are of two kinds:
//   - shooting: a round casts rays in proportion to the unshot power it shoots, plus about one ray
//     per weak shooter (ProgressiveSolver::PlanRound), and the unshot fraction falls by a steady
//     factor q a round. So the rounds left until the tolerance are log(tolerance / unshot) / log q,
//     and their rays a geometric series: rays = a * unshot_before + b per round, a and b fitted
//     to the rounds seen (b = 0 until two rounds differ).
//   - the final gather: exactly the rays ProgressiveSolver::PendingGatherRays says, each priced at
//     a shooting ray's cost times the ratio the caller measured (SetGatherRayCost).
// Time is seconds = overhead + rays / rate per round, fitted the same way (overhead 0 until two
// rounds differ), so rounds that shrink to a few rays still cost their fixed part.
// Elapsed time extrapolated in log(unshot), as if every round cost the same, would be several times
// too high, since the first rounds cast most of the shooting rays, and would reach 100% before the
// gather, which is most of a job's rays.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace radfarm {

// One round as it ran.
struct RoundSample {
  uint64_t rays = 0;
  double seconds = 0;        // wall time of the round alone
  double unshot_before = 0;  // unshot fraction before and after it
  double unshot_after = 0;
  bool gather = false;
};

// Where the solve stands now.
struct SolvePosition {
  uint64_t rays_done = 0;         // in every round applied
  double unshot_fraction = 1;     // after the last round applied
  uint64_t gather_rays_left = 0;  // ProgressiveSolver::PendingGatherRays
  // The round running now, if any: its planned rays and the part of them computed so far.
  uint64_t round_rays = 0;
  uint64_t round_rays_done = 0;
  double round_seconds = 0;   // spent in it so far
  bool round_gather = false;  // it is the final gather
  // What a budget leaves from now (nullopt: no such budget): the solve ends there if the rays and
  // seconds to convergence would run past it, so the estimate stops there too.
  std::optional<uint64_t> budget_rays_left{};
  std::optional<double> budget_seconds_left{};
  // The display's rays expected after the solve (core/display_budget.h DisplayRaysForecast),
  // priced as the gather's: the ETA includes them, the fraction (of the solve's rays) does not.
  uint64_t display_rays = 0;
};

struct ProgressEstimate {
  // Of the solve's rays, 0..1. Before a shooting round has been seen the rounds to come cannot be
  // sized: then the share of a ray budget spent, or 0 without one (a lower bound, so a display
  // that never lets it fall, core/progress_ratchet.h, does not stall at an early guess).
  double fraction = 0;
  std::optional<double>
      seconds_left;        // nullopt until a round has been timed; the display's included
  uint64_t rays_left = 0;  // predicted, the running round's rest included
};

class ProgressEstimator {
 public:
  explicit ProgressEstimator(double tolerance) : tolerance_(tolerance) {}

  void AddRound(const RoundSample& round);
  // Seconds per gather ray over seconds per shooting ray (core/ray_cost_probe.h): the gather
  // still to come is priced at the fitted rate times this. 1 until set (or when set to <= 0).
  void SetGatherRayCost(double relative) { gather_ray_cost_ = relative > 0 ? relative : 1; }
  ProgressEstimate Estimate(const SolvePosition& now) const;

  // The shooting rounds and rays still to come from `unshot` on (none at or below the tolerance);
  // nullopt when no shooting round has been seen to fit them to.
  struct Shooting {
    double rounds = 0;
    double rays = 0;
  };
  std::optional<Shooting> ShootingLeft(double unshot) const;
  // The rays of a shooting round that starts at `unshot`, as fitted.
  double ShootingRoundRays(double unshot) const;
  // The seconds `rounds` rounds of `rays` rays in all take, at the fitted rate and overhead;
  // nullopt before any round was timed.
  std::optional<double> Seconds(double rays, double rounds) const;

 private:
  // Estimate without the display that follows the solve.
  ProgressEstimate SolveEstimate(const SolvePosition& now) const;

  // The rounds the fits use: the last kWindow shooting rounds for rays (older ones describe a
  // solve that has moved on); up to kTimedWindow rounds for time, so the big early rounds anchor
  // the rate: the last rounds cast a few rays each, and a rate fitted to them alone is mostly
  // their fixed cost, and the ETA it gives far too high.
  static constexpr size_t kWindow = 4;
  static constexpr size_t kTimedWindow = 64;

  double tolerance_;
  double gather_ray_cost_ = 1;
  std::vector<RoundSample> shooting_;  // the last kWindow shooting rounds
  std::vector<RoundSample> timed_;     // the last kTimedWindow rounds of any kind
};

}  // namespace radfarm
