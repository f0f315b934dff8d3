// RoundDriver: the one round loop. Driven by hand, with batches computed in any order, it gives
// Solve's bits; its state resumes anywhere; it stops for the reasons the stopping rules give.
#include "solve/round_driver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "core/batch_tracer.h"
#include "core/solve_control.h"
#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::MakeClosedBox;
using testing::Surface;

PatchScene LitBox() {
  PatchScene scene = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, Surface{{0.6, 0.5, 0.4}, {}, 0});
  scene.patches[4].emission = {3, 3, 3};
  return scene;
}

SolverSettings Settings() {
  SolverSettings s;
  s.shot_rays = 1 << 12;
  s.tolerance = 0.01;
  s.threads = 1;
  return s;
}

// Runs the driver's rounds one batch at a time, last batch first, with small batches.
SolveResult DriveBackwards(RoundDriver& driver, std::vector<SolveState>* states = nullptr) {
  BatchTracer runner(driver.scene(), driver.caster(), driver.solver().sampler());
  while (std::optional<RoundPlan> plan = driver.PlanNext(97, 0)) {
    std::vector<BatchResult> results(plan->batches.size());
    for (size_t b = plan->batches.size(); b-- > 0;) results[b] = runner.Run(plan->batches[b]);
    driver.Apply(*plan, results, 0);
    if (states != nullptr) states->push_back(driver.State());
  }
  return driver.Finish(0, 1);
}

TEST(RoundDriverTest, BatchesInAnyOrderAndSizeGiveSolvesBits) {
  const PatchScene scene = LitBox();
  const SolveResult solved = Solve(scene, Settings());
  std::unique_ptr<RoundDriver> driver = RoundDriver::Start(scene, Settings(), nullptr);
  const SolveResult driven = DriveBackwards(*driver);
  EXPECT_EQ(driven.radiosity, solved.radiosity);
  EXPECT_EQ(driven.unshot, solved.unshot);
  EXPECT_EQ(driven.stats.rays, solved.stats.rays);
  EXPECT_EQ(driven.stats.rounds, solved.stats.rounds);
  EXPECT_EQ(driven.stats.stop_reason, kStopConverged);
  // Stopped: no further plan, the same reason.
  EXPECT_FALSE(driver->PlanNext(97, 0).has_value());
  EXPECT_EQ(driver->stop_reason(), std::optional<std::string>(kStopConverged));
}

TEST(RoundDriverTest, ResumesFromEveryRoundBoundary) {
  const PatchScene scene = LitBox();
  std::vector<SolveState> states;
  std::unique_ptr<RoundDriver> whole = RoundDriver::Start(scene, Settings(), nullptr);
  const SolveResult all = DriveBackwards(*whole, &states);
  ASSERT_GE(states.size(), 3u);
  for (const SolveState& state : states) {
    SCOPED_TRACE("round " + std::to_string(state.round));
    std::unique_ptr<RoundDriver> resumed = RoundDriver::Start(scene, Settings(), &state);
    EXPECT_EQ(resumed->totals().rays, state.totals.rays);
    const SolveResult rest = DriveBackwards(*resumed);
    EXPECT_EQ(rest.radiosity, all.radiosity);
    EXPECT_EQ(rest.stats.rays, all.stats.rays);
    EXPECT_EQ(rest.stats.rounds, all.stats.rounds);
  }
}

// Paced rounds (a ray budget far below what the rounds need at full strength) are planned from
// the state alone: a solve resumed at any round boundary paces, stops and ends as one run through.
TEST(RoundDriverTest, APacedBudgetResumesFromEveryRoundBoundary) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Settings();
  settings.max_rays = 1500;
  std::vector<SolveState> states;
  std::unique_ptr<RoundDriver> whole = RoundDriver::Start(scene, settings, nullptr);
  const SolveResult all = DriveBackwards(*whole, &states);
  const SolveResult full = DriveBackwards(*RoundDriver::Start(scene, Settings(), nullptr));
  ASSERT_GT(full.stats.rays, 5 * settings.max_rays);
  EXPECT_LE(all.stats.rays, settings.max_rays);
  ASSERT_GE(states.size(), 3u);
  for (const SolveState& state : states) {
    SCOPED_TRACE("round " + std::to_string(state.round));
    std::unique_ptr<RoundDriver> resumed = RoundDriver::Start(scene, settings, &state);
    const SolveResult rest = DriveBackwards(*resumed);
    EXPECT_EQ(rest.radiosity, all.radiosity);
    EXPECT_EQ(rest.stats.rays, all.stats.rays);
    EXPECT_EQ(rest.stats.rounds, all.stats.rounds);
    EXPECT_EQ(rest.stats.stop_reason, all.stats.stop_reason);
  }
}

TEST(RoundDriverTest, ADriverOwningItsSceneGivesTheSameBitsAndResumes) {
  const PatchScene scene = LitBox();
  std::vector<SolveState> states;
  std::unique_ptr<RoundDriver> borrowing = RoundDriver::Start(scene, Settings(), nullptr);
  const SolveResult all = DriveBackwards(*borrowing, &states);
  Result<std::unique_ptr<RoundDriver>> owning =
      RoundDriver::StartOwning(PatchScene(scene), Settings(), nullptr);
  ASSERT_TRUE(owning.ok()) << owning.error();
  EXPECT_EQ((*owning)->mesh(), nullptr);
  const SolveResult owned = DriveBackwards(**owning);
  EXPECT_EQ(owned.radiosity, all.radiosity);
  EXPECT_EQ(owned.unshot, all.unshot);
  ASSERT_GE(states.size(), 2u);
  Result<std::unique_ptr<RoundDriver>> resumed =
      RoundDriver::StartOwning(PatchScene(scene), Settings(), &states[1]);
  ASSERT_TRUE(resumed.ok()) << resumed.error();
  EXPECT_EQ(DriveBackwards(**resumed).radiosity, all.radiosity);
}

TEST(RoundDriverTest, ADriverOwningItsSceneRefusesAStateOfAnotherSize) {
  SolveState state;
  state.radiosity.resize(2);
  state.unshot.resize(2);
  Result<std::unique_ptr<RoundDriver>> driver =
      RoundDriver::StartOwning(LitBox(), Settings(), &state);
  ASSERT_FALSE(driver.ok());
  EXPECT_NE(driver.error().find("holds 2 elements"), std::string::npos) << driver.error();
}

TEST(RoundDriverTest, TheBudgetsStopIt) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Settings();
  settings.tolerance = 1e-6;
  settings.max_rays = 5000;
  std::unique_ptr<RoundDriver> driver = RoundDriver::Start(scene, settings, nullptr);
  const SolveResult r = DriveBackwards(*driver);
  EXPECT_EQ(r.stats.stop_reason, kStopRayBudget);
  EXPECT_LE(r.stats.rays, settings.max_rays);

  settings.max_rays = 0;
  settings.max_seconds = 1;
  driver = RoundDriver::Start(scene, settings, nullptr);
  EXPECT_FALSE(driver->PlanNext(97, 1.5).has_value());  // the seconds are the caller's
  EXPECT_EQ(driver->stop_reason(), std::optional<std::string>(kStopTimeBudget));
}

// A 10 s budget ran a 23 s first round. With the caller's pace the round is trimmed to
// the rays that fit in the seconds left, and it ends the solve with the time budget's reason.
TEST(RoundDriverTest, ARoundIsPacedToTheTimeLeftAtTheCallersPace) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Settings();
  settings.tolerance = 1e-6;
  settings.max_seconds = 10;
  std::unique_ptr<RoundDriver> driver = RoundDriver::Start(scene, settings, nullptr);
  const std::optional<RoundPlan> whole = driver->PlanNext(97, 0);  // no pace: not trimmed
  ASSERT_TRUE(whole.has_value());
  EXPECT_FALSE(whole->capped);
  ASSERT_GT(whole->rays, 1000u);
  // The rounds stop at the solve's share of the 10 s (SolveBudget).
  const double solve_seconds = driver->budget().max_seconds;
  ASSERT_GT(solve_seconds, 2.5);
  ASSERT_LT(solve_seconds, 10);
  // 2 s left at 300 rays/s: 600 rays, less than this round and the rounds after it need at full
  // strength, so the round gets its share of them (PacedRoundCap) and the solve goes on; when the
  // time is up, it stops.
  const std::optional<RoundPlan> paced = driver->PlanNext(97, solve_seconds - 2, 300);
  ASSERT_TRUE(paced.has_value());
  EXPECT_FALSE(paced->capped);
  EXPECT_GT(paced->rays, 0u);
  EXPECT_LT(paced->rays, 600u);
  BatchTracer runner(driver->scene(), driver->caster(), driver->solver().sampler());
  std::vector<BatchResult> results;
  for (const Batch& b : paced->batches) results.push_back(runner.Run(b));
  driver->Apply(*paced, results, solve_seconds - 0.5);
  EXPECT_EQ(driver->stop_reason(), std::nullopt);
  EXPECT_FALSE(driver->PlanNext(97, solve_seconds, 300).has_value());
  EXPECT_EQ(driver->stop_reason(), std::optional<std::string>(kStopTimeBudget));
  EXPECT_EQ(driver->totals().rays, paced->rays);

  // A pace that fits the whole round trims nothing and the solve goes on.
  driver = RoundDriver::Start(scene, settings, nullptr);
  const std::optional<RoundPlan> fits = driver->PlanNext(97, 1, 1e9);
  ASSERT_TRUE(fits.has_value());
  EXPECT_FALSE(fits->capped);
  EXPECT_EQ(fits->rays, whole->rays);
  // A ray budget smaller than the time's cap stays a ray budget: its rounds are paced to it, and
  // the last spends it exactly.
  settings.max_rays = 100;
  driver = RoundDriver::Start(scene, settings, nullptr);
  BatchTracer rays_runner(driver->scene(), driver->caster(), driver->solver().sampler());
  while (const std::optional<RoundPlan> rays = driver->PlanNext(97, 1, 1e9)) {
    EXPECT_LE(driver->totals().rays + rays->rays, 100u);
    results.clear();
    for (const Batch& b : rays->batches) results.push_back(rays_runner.Run(b));
    driver->Apply(*rays, results, 1.5);
  }
  EXPECT_EQ(driver->stop_reason(), std::optional<std::string>(kStopRayBudget));
  EXPECT_EQ(driver->totals().rays, 100u);
}

TEST(RoundDriverTest, AStateOfAnotherSizeIsRefused) {
  const PatchScene scene = LitBox();
  SolveState state;
  state.radiosity.resize(2);
  state.unshot.resize(2);
  EXPECT_THROW(RoundDriver::Start(scene, Settings(), &state), std::invalid_argument);
}

}  // namespace
}  // namespace radfarm
