// The final gather (SolverSettings::gather_rays): against closed forms, the shooting solve it
// replaces, and the determinism and resume contracts of core/batch.h.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "core/batch_tracer.h"
#include "core/direct_light.h"
#include "core/display_budget.h"
#include "core/gathering_patches.h"
#include "core/ray_caster.h"
#include "core/solve_control.h"
#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::Gathering;
using testing::LitBox;
using testing::MakeClosedBox;
using testing::Surface;

// Few shot rays, so that the gather does most of the work.
constexpr uint64_t kShotRays = 1 << 16;

// Furnace: B = E / (1 - rho) on every patch. With six emitter faces the solve starts from the
// direct light (96 shadow rays per patch, under the gather's 1024); with 64 gather rays it may
// not, so the emitters shoot and the gather takes all the light.
TEST(GatherTest, FurnaceWithAndWithoutTheDirectLightStart) {
  const double rho = 0.5, exact = 1 / (1 - rho);
  const PatchScene scene =
      MakeClosedBox({0, 0, 0}, {1, 1, 1}, 1, Surface{{rho, rho, rho}, {1, 1, 1}, 0});
  for (uint32_t gather_rays : {1024u, 64u}) {
    SolverSettings settings = Gathering(gather_rays, kShotRays);
    settings.tolerance = 1e-4;
    const ProgressiveSolver probe(scene, settings);
    EXPECT_EQ(probe.direct_light().empty(), gather_rays == 64) << gather_rays;
    const SolveResult r = Solve(scene, settings);
    for (const Rgb& b : r.radiosity) {
      EXPECT_NEAR(b.g, exact, 0.01 * exact) << gather_rays;
    }
    EXPECT_EQ(r.unshot, std::vector<Rgb>(scene.patches.size())) << "a gathered solve has no unshot";
    EXPECT_EQ(r.stats.stop_reason, kStopConverged);
  }
}

// Two facing unit squares at distance 1 in open space, E1 = 1, rho = 0.5 (the shooting test's
// closed form): B1 = 1.010083, B2 = 0.100920. The direct light on B2 is computed, not counted.
// The ETA's view of the gather: every reflecting patch's rays after each shooting round, none
// after the gather round.
TEST(GatherTest, PendingGatherRaysUntilTheGatherRuns) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Gathering(256, kShotRays);
  const uint64_t all = uint64_t{256} * scene.patches.size();  // every patch of the lit box reflects
  EXPECT_EQ(ProgressiveSolver(scene, settings).PendingGatherRays(), all);
  std::vector<std::pair<bool, uint64_t>> rounds;  // (gather round, gather rays left)
  Solve(scene, settings, [&](const RoundProgress& p) {
    rounds.push_back({p.gather, p.gather_rays_left});
  });
  ASSERT_GE(rounds.size(), 2u);
  for (size_t r = 0; r + 1 < rounds.size(); ++r) {
    EXPECT_FALSE(rounds[r].first) << r;
    EXPECT_EQ(rounds[r].second, all) << r;
  }
  EXPECT_TRUE(rounds.back().first);
  EXPECT_EQ(rounds.back().second, 0u);
  settings.gather_rays = 0;
  EXPECT_EQ(ProgressiveSolver(scene, settings).PendingGatherRays(), 0u);
}

// The gather's batches are keyed by kGatherRound, not by the round it runs in, and planned ahead
// they are the ones the gather round has: a solve that needs more shooting rounds to reach its
// tolerance gathers with the same rays, and a farm may trace them before it gets there.
TEST(GatherTest, TheGatherRoundIsTheOnePlannedAheadWhicheverRoundItRunsIn) {
  const PatchScene scene = LitBox();
  const RayCaster caster(scene);
  std::vector<RoundPlan> gathers;
  for (double tolerance : {0.2, 0.01}) {
    SolverSettings settings = Gathering(64, kShotRays);
    settings.tolerance = tolerance;
    ProgressiveSolver solver(scene, settings);
    const RoundPlan ahead = solver.PlanPendingGather(100);
    ASSERT_FALSE(ahead.batches.empty());
    BatchTracer tracer(scene, caster, solver.sampler());
    for (;;) {
      const RoundPlan plan = solver.PlanRound(100);
      ASSERT_FALSE(plan.batches.empty());
      if (plan.gather) {
        EXPECT_EQ(plan.round, solver.rounds_done());
        ASSERT_EQ(plan.batches.size(), ahead.batches.size());
        for (size_t k = 0; k < plan.batches.size(); ++k) {
          EXPECT_EQ(plan.batches[k].round, kGatherRound);
          EXPECT_EQ(plan.batches[k].shooter, ahead.batches[k].shooter);
          EXPECT_EQ(plan.batches[k].first_ray, ahead.batches[k].first_ray);
          EXPECT_EQ(plan.batches[k].ray_count, ahead.batches[k].ray_count);
        }
        gathers.push_back(plan);
      } else {
        for (const Batch& b : plan.batches) EXPECT_EQ(b.round, plan.round);
      }
      std::vector<BatchResult> results;
      for (const Batch& b : plan.batches) results.push_back(tracer.Run(b));
      solver.ApplyRound(plan, results);
      if (plan.gather) break;
    }
    EXPECT_TRUE(solver.PlanPendingGather(100).batches.empty()) << "the gather ran";
  }
  ASSERT_EQ(gathers.size(), 2u);
  EXPECT_LT(gathers[0].round, gathers[1].round) << "the tighter tolerance shoots more rounds";
}

TEST(GatherTest, TwoFacingSquaresInOpenSpace) {
  PatchScene scene;
  testing::AddQuadGrid({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1,
                       Surface{{0.5, 0.5, 0.5}, {1, 1, 1}, 0}, &scene);
  testing::AddQuadGrid({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 1,
                       Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  SolverSettings settings = Gathering(1 << 16, kShotRays);
  settings.tolerance = 1e-6;
  const SolveResult r = Solve(scene, settings);
  EXPECT_NEAR(r.radiosity[0].g, 1.010083, 1e-3);
  EXPECT_NEAR(r.radiosity[1].g, 0.100920, 1e-3);
  std::printf("facing squares: B1 %.6f B2 %.6f\n", r.radiosity[0].g, r.radiosity[1].g);
}

// On a box of 96 patches the gathered solve is closer to a converged shooting solve than a
// shooting solve casting at least as many rays is.
TEST(GatherTest, BeatsShootingAtEqualRaysOnALitBox) {
  const PatchScene scene = LitBox();
  SolverSettings fine;
  fine.shot_rays = 1 << 24;
  fine.tolerance = 1e-4;
  fine.threads = 2;
  const SolveResult reference = Solve(scene, fine);
  const SolveResult gathered = Solve(scene, Gathering(1024, kShotRays));
  SolverSettings shooting = fine;
  shooting.tolerance = 1e-3;
  shooting.shot_rays = gathered.stats.rays / 2;  // a shot's light bounces: about 2x the rays
  const SolveResult shot = Solve(scene, shooting);
  const auto rms = [&](const std::vector<Rgb>& b) {
    double sum = 0;
    for (size_t i = 0; i < b.size(); ++i) {
      const double rel = (b[i].Sum() - reference.radiosity[i].Sum()) / reference.radiosity[i].Sum();
      sum += rel * rel;
    }
    return std::sqrt(sum / double(b.size()));
  };
  const double gather_error = rms(gathered.radiosity), shoot_error = rms(shot.radiosity);
  std::printf("lit box: gathered %.4f, shooting %.4f RMS relative error (%llu, %llu rays)\n",
              gather_error, shoot_error, static_cast<unsigned long long>(gathered.stats.rays),
              static_cast<unsigned long long>(shot.stats.rays));
  EXPECT_GE(shot.stats.rays, gathered.stats.rays);
  EXPECT_LT(gather_error, shoot_error);
}

TEST(GatherTest, SameBitsWithAnyThreadCount) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Gathering(1024, kShotRays);
  settings.threads = 1;
  const SolveResult one = Solve(scene, settings);
  for (uint32_t threads : {2u, 7u}) {
    settings.threads = threads;
    EXPECT_TRUE(BitIdentical(Solve(scene, settings).radiosity, one.radiosity)) << threads;
  }
}

// Resuming from the checkpoint just before the gather round, or from the gathered state, gives
// the same bits; the gathered state runs no more rounds.
TEST(GatherTest, ResumesBeforeAndAfterTheGatherRound) {
  const PatchScene scene = LitBox();
  const SolverSettings settings = Gathering(1024, kShotRays);
  std::vector<SolveState> checkpoints;
  const SolveResult whole =
      Solve(scene, settings, {}, nullptr, [&](const SolveState& c) { checkpoints.push_back(c); });
  ASSERT_GE(checkpoints.size(), 2u);
  for (size_t k : {checkpoints.size() - 2, checkpoints.size() - 1}) {
    const SolveResult resumed = Solve(scene, settings, {}, &checkpoints[k]);
    EXPECT_TRUE(BitIdentical(resumed.radiosity, whole.radiosity)) << k;
    EXPECT_EQ(resumed.stats.rays, whole.stats.rays) << k;
    EXPECT_EQ(resumed.stats.rounds, whole.stats.rounds) << k;
  }
}

// The max_rays whose solve keeps `solve_rays` (SolveBudget: the display after the solve keeps a
// quarter of max_rays).
uint64_t MaxRaysForSolve(const PatchScene& scene, SolverSettings settings, uint64_t solve_rays) {
  settings.max_rays = solve_rays + solve_rays / 3;
  while (SolveBudget(scene, settings).max_rays < solve_rays) ++settings.max_rays;
  while (SolveBudget(scene, settings).max_rays > solve_rays) --settings.max_rays;
  EXPECT_EQ(SolveBudget(scene, settings).max_rays, solve_rays);
  return settings.max_rays;
}

// A ray budget that runs out at the gather cuts it to the budget exactly (the solve's share of
// it) and says so; one too small for its share of rays per patch (kMinGatherShare) skips it.
TEST(GatherTest, RayBudgetCutsTheGatherRound) {
  const PatchScene scene = LitBox();
  SolverSettings settings = Gathering(1024, kShotRays);
  const SolveResult unlimited = Solve(scene, settings);
  const uint64_t gather_rays = uint64_t{settings.gather_rays} * scene.patches.size();
  const uint64_t shooting_rays = unlimited.stats.rays - gather_rays;
  // The start's shadow rays count against the budget too (so a budget also plans a cheaper start:
  // the start's rays differ between the budgets, each within a quarter of its budget).
  settings.max_rays = MaxRaysForSolve(scene, settings, shooting_rays + gather_rays / 3);
  const SolveResult cut = Solve(scene, settings);
  EXPECT_GT(cut.stats.start_rays, 0u);
  EXPECT_LE(cut.stats.start_rays, settings.max_rays / kStartBudgetShare);
  // The display after the solve keeps a quarter (core/display_budget.h).
  ASSERT_TRUE(DisplayCastsRays(scene, settings));
  EXPECT_EQ(cut.stats.rays + cut.stats.start_rays,
            settings.max_rays - settings.max_rays / kDisplayBudgetShare);
  EXPECT_EQ(cut.stats.stop_reason, kStopRayBudget);
  EXPECT_EQ(cut.unshot, std::vector<Rgb>(scene.patches.size()));
  // A gather needs gather_rays / kMinGatherShare rays per patch: one ray short, it is skipped;
  // with them, it runs, each patch with its share.
  const uint64_t least = scene.patches.size() * (settings.gather_rays / kMinGatherShare);
  settings.max_rays =
      MaxRaysForSolve(scene, settings, cut.stats.start_rays + shooting_rays + least - 1);
  const SolveResult skipped = Solve(scene, settings);
  EXPECT_EQ(skipped.stats.start_rays, cut.stats.start_rays);
  EXPECT_EQ(skipped.stats.rays, shooting_rays);
  EXPECT_EQ(skipped.stats.stop_reason, kStopRayBudget);
  EXPECT_FALSE(skipped.unshot == std::vector<Rgb>(scene.patches.size()));
  settings.max_rays =
      MaxRaysForSolve(scene, settings, cut.stats.start_rays + shooting_rays + least);
  const SolveResult least_gather = Solve(scene, settings);
  EXPECT_EQ(least_gather.stats.rays, shooting_rays + least);
  EXPECT_EQ(least_gather.unshot, std::vector<Rgb>(scene.patches.size()));
}

// A closed room of two-sided walls (a Blender room with outward normals): each wall's outer layer
// faces the void, so its gather rays would all escape: it is not gathered, and the solve reports
// no escaped rays. Its radiosity is what the gather would have made of it: none.
TEST(GatherTest, TheOuterLayerOfAClosedRoomIsNotGathered) {
  PatchScene scene = LitBox();
  const size_t inner = scene.patches.size();
  for (size_t i = 0; i < inner; ++i) {
    Patch back = scene.patches[i];
    std::reverse(back.corners.begin(), back.corners.begin() + back.corner_count);
    back.normal = -back.normal;
    back.surface += 6;
    back.emission = {};
    scene.patches[i].two_sided = back.two_sided = true;
    scene.patches.push_back(back);
  }
  const SolverSettings settings = Gathering(256, kShotRays);
  const ProgressiveSolver solver(scene, settings);
  EXPECT_EQ(solver.GatheringPatches(), inner);
  EXPECT_EQ(solver.PendingGatherRays(), inner * 256);
  const RoundPlan gather = solver.PlanPendingGather(4096);
  ASSERT_EQ(gather.shots.size(), inner);
  for (const Shot& shot : gather.shots) EXPECT_LT(shot.shooter, inner);

  const SolveResult r = Solve(scene, settings);
  EXPECT_EQ(r.stats.escaped_rays, 0u);
  for (size_t i = inner; i < scene.patches.size(); ++i) EXPECT_EQ(r.radiosity[i], Rgb()) << i;
  for (size_t i = 0; i < inner; ++i) EXPECT_GT(r.radiosity[i].g, 0) << i;
}

TEST(GatherTest, OnlyAPatchWithTheWholeSceneBehindItFacesTheVoid) {
  const PatchScene box = LitBox();
  Bounds3 bounds;
  bounds.Extend({0, 0, 0});
  bounds.Extend({1, 1, 1});
  for (const Patch& p : box.patches) {
    EXPECT_FALSE(FacesTheVoid(p, bounds));  // facing in: the room is in front
    Patch out = p;
    out.normal = -p.normal;
    EXPECT_TRUE(FacesTheVoid(out, bounds));  // facing out of the bounds
  }
  // A floor inside a larger scene, facing down with a basement under it: not the void.
  Patch floor = box.patches.front();
  bounds.Extend({0, -5, 0});
  floor.normal = {0, -1, 0};
  floor.centre = {0.5, 0, 0.5};
  EXPECT_FALSE(FacesTheVoid(floor, bounds));
}

// The energy account balances after every round, the gather round included.
TEST(GatherTest, EnergyBalancesEveryRound) {
  PatchScene scene = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, Surface{{0.7, 0.4, 0.2}, {}, 0});
  scene.patches.resize(scene.patches.size() - 9);  // open: light escapes
  scene.patches[3 * 9 + 4].emission = {5, 5, 5};
  int rounds = 0;
  Solve(scene, Gathering(1024, kShotRays), [&](const RoundProgress& p) {
    const EnergyAccount& e = *p.energy;
    EXPECT_NEAR(e.emitted, e.absorbed + e.unshot + e.escaped, 1e-12 * e.emitted);
    EXPECT_GT(e.escaped, 0);
    ++rounds;
  });
  EXPECT_GT(rounds, 2);
}

}  // namespace
}  // namespace radfarm
