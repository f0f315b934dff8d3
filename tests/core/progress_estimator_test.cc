// ProgressEstimator against made-up solves whose every round is known in advance: rays in
// proportion to the unshot power plus a floor, a steady decay, a fixed rate and per-round
// overhead, then a gather. No clock: the "seconds" are computed.
#include "core/progress_estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace radfarm {
namespace {

struct FakeSolve {
  double unshot0 = 0.5;
  double decay = 0.4;
  double rays_per_unshot = 1e6;
  double floor_rays = 2000;
  double rays_per_second = 2e6;
  double overhead_seconds = 0.02;
  double gather_ray_cost = 1;  // a gather ray's time over a shooting ray's
  double tolerance = 1e-3;
  uint64_t gather_rays = 5'000'000;

  // Every round, the gather last.
  std::vector<RoundSample> Rounds() const {
    std::vector<RoundSample> rounds;
    for (double u = unshot0; u > tolerance; u *= decay) {
      const auto rays = uint64_t(rays_per_unshot * u + floor_rays);
      rounds.push_back({rays, Seconds(rays), u, u * decay, false});
    }
    const double last = rounds.back().unshot_after;
    rounds.push_back({gather_rays,
                      overhead_seconds + gather_ray_cost * double(gather_rays) / rays_per_second,
                      last, 0, true});
    return rounds;
  }
  double Seconds(uint64_t rays) const { return overhead_seconds + double(rays) / rays_per_second; }
};

// The position after rounds [0, k) of `rounds`.
SolvePosition After(const std::vector<RoundSample>& rounds, size_t k, uint64_t gather_rays) {
  SolvePosition at;
  for (size_t i = 0; i < k; ++i) at.rays_done += rounds[i].rays;
  at.unshot_fraction = rounds[k - 1].unshot_after;
  at.gather_rays_left = rounds[k - 1].gather ? 0 : gather_rays;
  return at;
}

// The most rays of rounds [0, k) over the fewest: the estimator fits a fixed cost a round only
// once this reaches 10 (before, a ray's cost varies more than the fixed cost shows).
double Spread(const std::vector<RoundSample>& rounds, size_t k) {
  double fewest = INFINITY, most = 0;
  for (size_t i = 0; i < k; ++i) {
    fewest = std::min(fewest, double(rounds[i].rays));
    most = std::max(most, double(rounds[i].rays));
  }
  return most / fewest;
}

double SecondsFrom(const std::vector<RoundSample>& rounds, size_t k) {
  double s = 0;
  for (size_t i = k; i < rounds.size(); ++i) s += rounds[i].seconds;
  return s;
}

TEST(ProgressEstimatorTest, NothingIsKnownBeforeTheFirstRound) {
  ProgressEstimator estimator(1e-3);
  const ProgressEstimate e = estimator.Estimate({0, 1.0, 1000, 0, 0, 0, false});
  EXPECT_FALSE(e.seconds_left.has_value());
  EXPECT_EQ(e.fraction, 0);
}

TEST(ProgressEstimatorTest, WithinThirtyPercentFromTheFirstRoundAndExactOnceTheModelIsFitted) {
  const FakeSolve solve;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ASSERT_GE(rounds.size(), 6u);
  ProgressEstimator estimator(solve.tolerance);
  for (size_t k = 1; k < rounds.size(); ++k) {
    estimator.AddRound(rounds[k - 1]);
    const ProgressEstimate e = estimator.Estimate(After(rounds, k, solve.gather_rays));
    const double actual = SecondsFrom(rounds, k);
    ASSERT_TRUE(e.seconds_left.has_value()) << "after round " << k;
    EXPECT_NEAR(*e.seconds_left, actual, 0.3 * actual) << "after round " << k;
    // Once the rays are fitted with their floor (third round) and the times with their fixed
    // cost (rounds ten times apart): exact, but for the rounding of the round count.
    if (k >= 3 && Spread(rounds, k) >= 10) {
      EXPECT_NEAR(*e.seconds_left, actual, 0.02 * actual) << "after round " << k;
    }
  }
}

// The old estimate put progress at 100% once the unshot power reached the tolerance, before the
// gather that casts most of the rays.
// The 2x2 building's gather rays cost about half a first-round ray: priced at the shooting rate,
// the ETA was 35-43% too high until the gather began (progress_bench).
TEST(ProgressEstimatorTest, TheGatherStillToComeIsPricedAtItsMeasuredCost) {
  FakeSolve solve;
  solve.gather_ray_cost = 0.45;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator unaware(solve.tolerance), told(solve.tolerance);
  told.SetGatherRayCost(solve.gather_ray_cost);
  for (size_t k = 1; k + 1 < rounds.size(); ++k) {
    unaware.AddRound(rounds[k - 1]);
    told.AddRound(rounds[k - 1]);
    const SolvePosition at = After(rounds, k, solve.gather_rays);
    const double actual = SecondsFrom(rounds, k);
    EXPECT_GT(*unaware.Estimate(at).seconds_left, 1.3 * actual) << "after round " << k;
    if (k >= 3 && Spread(rounds, k) >= 10) {
      EXPECT_NEAR(*told.Estimate(at).seconds_left, actual, 0.02 * actual) << k;
    }
  }
  // Nothing else moves: the rays and the progress are the same.
  const SolvePosition at = After(rounds, 3, solve.gather_rays);
  EXPECT_EQ(told.Estimate(at).rays_left, unaware.Estimate(at).rays_left);
  EXPECT_EQ(told.Estimate(at).fraction, unaware.Estimate(at).fraction);
  // A ratio not measured (0) leaves the shooting rate.
  told.SetGatherRayCost(0);
  EXPECT_EQ(*told.Estimate(at).seconds_left, *unaware.Estimate(at).seconds_left);
}

// A bar that said "ETA 1s" before a 24 s display: the display's forecast rays are priced as the
// gather's, in the seconds and not in the solve's fraction.
TEST(ProgressEstimatorTest, TheEtaIncludesTheDisplayThatFollows) {
  FakeSolve solve;
  solve.gather_ray_cost = 0.5;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  estimator.SetGatherRayCost(solve.gather_ray_cost);
  for (size_t k = 0; k < 4; ++k) estimator.AddRound(rounds[k]);
  const SolvePosition solve_alone = After(rounds, 4, solve.gather_rays);
  SolvePosition with_display = solve_alone;
  with_display.display_rays = 3 * solve.gather_rays;
  const ProgressEstimate a = estimator.Estimate(solve_alone);
  const ProgressEstimate b = estimator.Estimate(with_display);
  ASSERT_TRUE(a.seconds_left && b.seconds_left);
  const double ray_seconds = *estimator.Seconds(1e6, 0) / 1e6;
  EXPECT_NEAR(*b.seconds_left - *a.seconds_left,
              double(with_display.display_rays) * solve.gather_ray_cost * ray_seconds,
              1e-9 * *b.seconds_left);
  EXPECT_EQ(b.fraction, a.fraction);
  EXPECT_EQ(b.rays_left, a.rays_left);
  // Once the solve is done nothing is left to price it against: no ETA appears from nothing.
  ProgressEstimator fresh(solve.tolerance);
  EXPECT_FALSE(fresh.Estimate(with_display).seconds_left);
}

TEST(ProgressEstimatorTest, ProgressCountsTheGatherStillToCome) {
  const FakeSolve solve;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  const size_t shooting = rounds.size() - 1;
  for (size_t k = 0; k < shooting; ++k) estimator.AddRound(rounds[k]);
  const ProgressEstimate before_gather =
      estimator.Estimate(After(rounds, shooting, solve.gather_rays));
  uint64_t shooting_rays = 0;
  for (size_t k = 0; k < shooting; ++k) shooting_rays += rounds[k].rays;
  EXPECT_NEAR(before_gather.fraction,
              double(shooting_rays) / double(shooting_rays + solve.gather_rays), 1e-9);
  EXPECT_LT(before_gather.fraction, 0.5);
  EXPECT_EQ(before_gather.rays_left, solve.gather_rays);
}

TEST(ProgressEstimatorTest, TheGatherShowsItsOwnProgressAndPace) {
  const FakeSolve solve;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  const size_t shooting = rounds.size() - 1;
  for (size_t k = 0; k < shooting; ++k) estimator.AddRound(rounds[k]);
  SolvePosition at = After(rounds, shooting, solve.gather_rays);
  at.round_rays = solve.gather_rays;
  at.round_gather = true;
  const double fitted = *estimator.Estimate(at).seconds_left;  // the whole gather, as fitted
  EXPECT_NEAR(fitted, rounds.back().seconds, 0.02 * rounds.back().seconds);
  double last_fraction = estimator.Estimate(at).fraction;
  for (uint64_t done : {1'000'000u, 2'500'000u, 4'000'000u, 5'000'000u}) {
    at.round_rays_done = done;
    at.round_seconds = 4.0 * double(done) / double(solve.gather_rays);  // slower than fitted
    const ProgressEstimate e = estimator.Estimate(at);
    EXPECT_GT(e.fraction, last_fraction) << done;
    last_fraction = e.fraction;
    // The rest between the fitted pace and the round's own (4 s for the whole gather), the more
    // its own the further it has come.
    const double part = double(done) / double(solve.gather_rays);
    const double own = 4.0 - at.round_seconds;
    const double as_fitted = std::max(0.0, fitted - at.round_seconds);
    ASSERT_TRUE(e.seconds_left.has_value());
    EXPECT_NEAR(*e.seconds_left, part * own + (1 - part) * as_fitted, 1e-9) << done;
    EXPECT_EQ(e.rays_left, solve.gather_rays - done);
  }
  EXPECT_DOUBLE_EQ(last_fraction, 1.0);
}

TEST(ProgressEstimatorTest, ARunningShootingRoundIsNotCountedTwice) {
  const FakeSolve solve;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  for (size_t k = 0; k < 3; ++k) estimator.AddRound(rounds[k]);
  SolvePosition between = After(rounds, 3, solve.gather_rays);
  SolvePosition running = between;
  running.round_rays = rounds[3].rays;
  const ProgressEstimate b = estimator.Estimate(between);
  const ProgressEstimate r = estimator.Estimate(running);
  EXPECT_NEAR(double(r.rays_left), double(b.rays_left), 0.01 * double(b.rays_left));
  EXPECT_NEAR(*r.seconds_left, *b.seconds_left, 0.01 * *b.seconds_left);
}

// Progress ran backwards on the farm: during the first round nothing sized the rounds to come,
// so the fraction counted the first round against the gather alone and climbed to 65-77 % on the
// building, then fell to 8 % when the second round started. A solve whose gather is about its
// first round's size, sampled during every round (a quarter at a time) and between rounds, from
// before the first round to the end: the fraction never falls by more than a point.
TEST(ProgressEstimatorTest, TheFractionDoesNotFallOverASolvesLife) {
  FakeSolve solve;
  solve.gather_rays = 500'000;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  SolvePosition between;
  between.unshot_fraction = solve.unshot0;
  between.gather_rays_left = solve.gather_rays;
  double last = 0;
  std::vector<double> seen;
  for (size_t k = 0; k < rounds.size(); ++k) {
    for (int quarter = 0; quarter <= 4; ++quarter) {
      SolvePosition at = between;
      at.round_rays = rounds[k].rays;
      at.round_rays_done = rounds[k].rays * quarter / 4;
      at.round_seconds = rounds[k].seconds * quarter / 4;
      at.round_gather = rounds[k].gather;
      const double fraction = estimator.Estimate(at).fraction;
      EXPECT_GE(fraction, last - 0.01) << "round " << k << ", quarter " << quarter;
      last = std::max(last, fraction);
      seen.push_back(fraction);
    }
    estimator.AddRound(rounds[k]);
    between = After(rounds, k + 1, solve.gather_rays);
    const double fraction = estimator.Estimate(between).fraction;
    EXPECT_GE(fraction, last - 0.01) << "after round " << k;
    last = std::max(last, fraction);
  }
  EXPECT_DOUBLE_EQ(last, 1.0);
  // Before the first round is applied the rounds to come are unknown: no share is claimed.
  for (int quarter = 0; quarter <= 4; ++quarter) EXPECT_EQ(seen[quarter], 0) << quarter;
}

// Under a ray budget the first round's fraction is the budget's share spent: a lower bound.
TEST(ProgressEstimatorTest, TheFirstRoundUnderARayBudgetShowsTheBudgetSpent) {
  ProgressEstimator estimator(1e-3);
  SolvePosition at{0, 1.0, 1000, 4000, 1000, 0.5, false};
  at.budget_rays_left = 9000;  // from the round's start: 10,000 less the 1,000 done
  EXPECT_DOUBLE_EQ(estimator.Estimate(at).fraction, 0.1);
}

TEST(ProgressEstimatorTest, ASolveThatStoppedConvergingStillGetsAFiniteEstimate) {
  ProgressEstimator estimator(1e-3);
  estimator.AddRound({1000, 1.0, 0.5, 0.5, false});
  const ProgressEstimate e = estimator.Estimate({1000, 0.5, 0, 0, 0, 0, false});
  ASSERT_TRUE(e.seconds_left.has_value());
  EXPECT_TRUE(std::isfinite(*e.seconds_left));
  EXPECT_GT(*e.seconds_left, 100.0);  // thousands of rounds at 1 s
}

TEST(ProgressEstimatorTest, DoneWhenNothingIsLeft) {
  ProgressEstimator estimator(1e-3);
  estimator.AddRound({1000, 1.0, 0.5, 1e-4, false});
  const ProgressEstimate e = estimator.Estimate({1000, 1e-4, 0, 0, 0, 0, false});
  EXPECT_DOUBLE_EQ(e.fraction, 1.0);
  EXPECT_EQ(e.rays_left, 0u);
  EXPECT_DOUBLE_EQ(*e.seconds_left, 0.0);
}

// A budget ends the solve where the rounds to convergence would run past it: the estimate ends
// there too (a --seconds 5 render on 88,750 patches showed "ETA 36s").
TEST(ProgressEstimatorTest, ABudgetEndsTheEstimateWhereItEndsTheSolve) {
  const FakeSolve solve;
  const std::vector<RoundSample> rounds = solve.Rounds();
  ProgressEstimator estimator(solve.tolerance);
  estimator.AddRound(rounds[0]);
  estimator.AddRound(rounds[1]);
  SolvePosition at = After(rounds, 2, solve.gather_rays);
  const ProgressEstimate free = estimator.Estimate(at);
  ASSERT_TRUE(free.seconds_left.has_value());
  ASSERT_GT(*free.seconds_left, 2.0);
  // A budget larger than the rest changes nothing.
  at.budget_seconds_left = 2 * *free.seconds_left;
  at.budget_rays_left = 2 * free.rays_left;
  const ProgressEstimate roomy = estimator.Estimate(at);
  EXPECT_EQ(roomy.rays_left, free.rays_left);
  EXPECT_DOUBLE_EQ(*roomy.seconds_left, *free.seconds_left);
  EXPECT_DOUBLE_EQ(roomy.fraction, free.fraction);
  // A second left: the ETA is that second, the rays and the bar in proportion.
  at.budget_seconds_left = 1.0;
  const ProgressEstimate timed = estimator.Estimate(at);
  EXPECT_DOUBLE_EQ(*timed.seconds_left, 1.0);
  EXPECT_NEAR(double(timed.rays_left), double(free.rays_left) / *free.seconds_left, 1.0);
  EXPECT_GT(timed.fraction, free.fraction);
  // Rays left fewer than the rest needs (and than the second's): the rays end it first.
  at.budget_rays_left = free.rays_left / 10;
  const ProgressEstimate rayed = estimator.Estimate(at);
  EXPECT_EQ(rayed.rays_left, free.rays_left / 10);
  EXPECT_DOUBLE_EQ(*rayed.seconds_left,
                   *free.seconds_left * double(free.rays_left / 10) / double(free.rays_left));
  const double done = double(at.rays_done);
  EXPECT_DOUBLE_EQ(rayed.fraction, done / (done + double(free.rays_left / 10)));
  // Spent: nothing left, done.
  at.budget_rays_left = 0;
  const ProgressEstimate spent = estimator.Estimate(at);
  EXPECT_EQ(spent.rays_left, 0u);
  EXPECT_DOUBLE_EQ(*spent.seconds_left, 0.0);
  EXPECT_DOUBLE_EQ(spent.fraction, 1.0);
}

}  // namespace
}  // namespace radfarm
