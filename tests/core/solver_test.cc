// The progressive solver against closed-form radiosity solutions (shared/reference/analytic.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "solve/local_solve.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::MakeClosedBox;
using testing::Surface;

SolverSettings FastSettings() {
  SolverSettings s;
  s.shot_rays = 1 << 18;
  s.threads = 2;
  return s;
}

// Furnace: a closed enclosure with uniform rho and E has B = E / (1 - rho) everywhere.
// Total rays grow as shot_rays / (1 - rho): light bounces about 1 / (1 - rho) times.
void ExpectFurnace(double rho, int patches_per_edge, uint64_t shot_rays, double tolerance) {
  const PatchScene scene =
      MakeClosedBox({0, 0, 0}, {1, 1, 1}, patches_per_edge, Surface{{rho, rho, rho}, {1, 1, 1}, 0});
  SolverSettings settings = FastSettings();
  settings.shot_rays = shot_rays;
  settings.tolerance = 1e-4;
  const SolveResult r = Solve(scene, settings);
  const double exact = 1 / (1 - rho);
  double worst = 0;
  for (const Rgb& b : r.radiosity) {
    ASSERT_TRUE(b.IsFinite());
    ASSERT_GT(b.Min(), 0);
    worst = std::max(worst, std::abs(b.r - exact) / exact);
  }
  std::printf("furnace rho=%g: worst relative error %.2e after %llu rounds, %llu rays\n", rho,
              worst, static_cast<unsigned long long>(r.stats.rounds),
              static_cast<unsigned long long>(r.stats.rays));
  EXPECT_LE(worst, tolerance) << "rho " << rho;
  EXPECT_EQ(r.stats.escaped_rays, 0u);
  EXPECT_EQ(r.stats.backface_hits, 0u);
}

TEST(FurnaceTest, HalfReflectance) { ExpectFurnace(0.5, 3, 1 << 18, 0.01); }
TEST(FurnaceTest, Reflectance0_9) { ExpectFurnace(0.9, 3, 1 << 17, 0.01); }
TEST(FurnaceTest, Reflectance0_99) { ExpectFurnace(0.99, 2, 1 << 14, 0.01); }

// Reflectance 0.999 converges without drift: the exact answer is 1000.
TEST(HardCaseTest, ReflectanceNearOneConverges) { ExpectFurnace(0.999, 1, 1 << 10, 0.01); }

// Emitted power = absorbed + unshot + escaped after every round, to rounding.
TEST(EnergyTest, BalancesEveryRound) {
  PatchScene scene = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, Surface{{0.7, 0.4, 0.2}, {}, 0});
  // Open the box: drop the +z face so some light escapes, and light a patch of the ceiling.
  scene.patches.resize(scene.patches.size() - 9);
  scene.patches[3 * 9 + 4].emission = {5, 4, 3};
  SolverSettings settings = FastSettings();
  int rounds = 0;
  Solve(scene, settings, [&](const RoundProgress& p) {
    const EnergyAccount& e = *p.energy;
    EXPECT_NEAR(e.emitted, e.absorbed + e.unshot + e.escaped, 1e-12 * e.emitted);
    ++rounds;
  });
  EXPECT_GT(rounds, 3);
}

// Cube with one patch per face, ceiling E = 1, rho = 0.5: exact radiosities from the reference.
TEST(SolverTest, CubeWithLitCeilingMatchesExactSolution) {
  PatchScene scene = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 1, Surface{{0.5, 0.5, 0.5}, {}, 0});
  scene.patches[3].emission = {1, 1, 1};  // +y face: the ceiling
  SolverSettings settings = FastSettings();
  settings.shot_rays = 1 << 22;
  settings.tolerance = 1e-5;
  const SolveResult r = Solve(scene, settings);
  EXPECT_NEAR(r.radiosity[3].r, 1.090909, 2e-3);
  EXPECT_NEAR(r.radiosity[2].r, 0.181746, 2e-3);  // floor
  for (int wall : {0, 1, 4, 5}) EXPECT_NEAR(r.radiosity[wall].r, 0.181836, 2e-3);
}

// Two facing unit squares at distance 1 in open space, E1 = 1, rho = 0.5:
// B1 = 1 / (1 - rho^2 F^2) = 1.010083, B2 = rho F B1 = 0.100920.
TEST(SolverTest, TwoFacingSquaresInOpenSpace) {
  PatchScene scene;
  testing::AddQuadGrid({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1,
                       Surface{{0.5, 0.5, 0.5}, {1, 1, 1}, 0}, &scene);
  testing::AddQuadGrid({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 1,
                       Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  SolverSettings settings = FastSettings();
  settings.shot_rays = 1 << 22;
  settings.tolerance = 1e-6;
  const SolveResult r = Solve(scene, settings);
  EXPECT_NEAR(r.radiosity[0].g, 1.010083, 1e-3);
  EXPECT_NEAR(r.radiosity[1].g, 0.100920, 1e-3);
  EXPECT_GT(r.stats.escaped_rays, 0u);
}

// A receiver of 1e-6 the area of a big emitter beside it: the huge A_i / A_j factor must not
// produce NaN, negative or runaway values, and the estimate must be statistically consistent.
TEST(HardCaseTest, TinyReceiverBesideHugeEmitter) {
  PatchScene scene;
  testing::AddQuadGrid({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}, 1,
                       Surface{{0, 0, 0}, {1, 1, 1}, 0}, &scene);
  const double h = 0.0005;  // receiver 1e-3 x 1e-3, facing down, 1 above the emitter's centre
  testing::AddQuadGrid({-h, -h, 1}, {-h, h, 1}, {h, h, 1}, {h, -h, 1}, 1,
                       Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  SolverSettings settings = FastSettings();
  settings.shot_rays = 1 << 23;
  const SolveResult r = Solve(scene, settings);
  const Rgb b = r.radiosity[1];
  ASSERT_TRUE(b.IsFinite());
  ASSERT_GE(b.Min(), 0);
  // Exact: B = rho * E * F(receiver -> emitter), F = 0.2394564705 (point under a square's centre).
  // Hits on the receiver are Poisson with mean N * F(emitter -> receiver) = N * 1e-6 * 0.2394...
  const double exact = 0.5 * 0.2394564705;
  const double expected_hits = double(settings.shot_rays) * 1e-6 * 0.2394564705;
  const double hits = b.r / exact * expected_hits;
  EXPECT_LE(std::abs(hits - expected_hits), 4 * std::sqrt(expected_hits) + 1)
      << "B=" << b.r << " exact " << exact;
}

// The same closed room translated by 1e5 in every axis gives the same solution.
TEST(HardCaseTest, FarFromOriginMatchesOrigin) {
  const Surface s{{0.6, 0.6, 0.6}, {}, 0};
  PatchScene near = MakeClosedBox({0, 0, 0}, {1, 1, 1}, 3, s);
  PatchScene far = MakeClosedBox({1e5, 1e5, 1e5}, {1e5 + 1, 1e5 + 1, 1e5 + 1}, 3, s);
  near.patches[3 * 9 + 4].emission = far.patches[3 * 9 + 4].emission = {1, 1, 1};
  const SolveResult a = Solve(near, FastSettings());
  const SolveResult b = Solve(far, FastSettings());
  ASSERT_EQ(a.radiosity.size(), b.radiosity.size());
  EXPECT_EQ(b.stats.escaped_rays, 0u);
  // Not bit-identical: patch areas and sample points computed at 1e5 differ in the last bits, so
  // a shot may get one ray more or less. Within 0.5 %, far below the noise of the estimate (~2 %).
  double worst = 0;
  for (size_t i = 0; i < a.radiosity.size(); ++i) {
    worst = std::max(worst, std::abs(a.radiosity[i].r - b.radiosity[i].r) / a.radiosity[i].r);
  }
  std::printf("far from origin: worst relative difference %.2e\n", worst);
  EXPECT_LE(worst, 5e-3);
}

// A budget far below what the rounds cast at full strength (the furnace at rho 0.9 takes about
// 2.6 M rays; at full strength 100,000 would not finish the first round, leaving 90 % of the light
// unshot): the rounds are paced to it, each casting the same share of its rays, and the solve
// converges within it or stops having spent it exactly.
TEST(SolverTest, RayBudgetPacesTheRounds) {
  const PatchScene scene =
      MakeClosedBox({0, 0, 0}, {1, 1, 1}, 2, Surface{{0.9, 0.9, 0.9}, {1, 1, 1}, 0});
  SolverSettings settings = FastSettings();
  const SolveResult full = Solve(scene, settings);
  settings.max_rays = 100000;
  ASSERT_GT(full.stats.rays, 20 * settings.max_rays);
  const SolveResult r = Solve(scene, settings);
  EXPECT_LE(r.stats.rays, settings.max_rays);
  if (r.stats.stop_reason == "ray budget") {
    EXPECT_EQ(r.stats.rays, settings.max_rays);
  }
  EXPECT_GT(r.stats.rounds, full.stats.rounds / 2);
  EXPECT_LT(r.stats.unshot_fraction, 0.01);
  // No light left unshot to darken it: the mean radiosity is the furnace's E / (1 - rho) = 10
  // within the noise of 100,000 rays.
  double mean = 0;
  for (const Rgb& b : r.radiosity) mean += b.r / double(r.radiosity.size());
  EXPECT_NEAR(mean, 10.0, 0.3);
}

// A budget smaller than one round: the rounds pace down to a ray a shooter, and the last casts
// what is left and no more (only the strongest shooters shoot when fewer rays are left than
// shooters).
TEST(SolverTest, RayBudgetBelowOneRoundSpendsTheBudgetAtMost) {
  const PatchScene scene =
      MakeClosedBox({0, 0, 0}, {1, 1, 1}, 2, Surface{{0.9, 0.9, 0.9}, {1, 1, 1}, 0});
  SolverSettings settings = FastSettings();
  settings.max_rays = 1000;
  const SolveResult r = Solve(scene, settings);
  EXPECT_GT(r.stats.rounds, 1u);
  EXPECT_LE(r.stats.rays, settings.max_rays);
  if (r.stats.stop_reason == "ray budget") {
    EXPECT_EQ(r.stats.rays, settings.max_rays);
  }
  // The grid cannot cut a shot: it shoots from fewer patches, at least one.
  settings.sampler = SamplerKind::kGrid;
  settings.grid_step_degrees = 10;  // 9 x 36 = 324 rays a shot
  const SolveResult g = Solve(scene, settings);
  EXPECT_EQ(g.stats.rays, 3u * 324u);
  settings.max_rays = 10;
  EXPECT_EQ(Solve(scene, settings).stats.rays, 324u);
}

}  // namespace
}  // namespace radfarm

namespace radfarm {
namespace {

// shooters_per_round keeps the patches with the most unshot power (ties: lower patch id), and the
// plan lists shots in patch order.
TEST(SolverTest, ShootersPerRoundKeepsTheStrongest) {
  PatchScene scene =
      testing::MakeClosedBox({0, 0, 0}, {1, 1, 1}, 1, testing::Surface{{0.5, 0.5, 0.5}, {}, 0});
  scene.patches[1].emission = {1, 1, 1};
  scene.patches[4].emission = {3, 3, 3};
  scene.patches[2].emission = {3, 3, 3};
  scene.patches[5].emission = {2, 2, 2};
  SolverSettings settings;
  settings.shooters_per_round = 2;
  const ProgressiveSolver solver(scene, settings);
  const RoundPlan plan = solver.PlanRound(1024);
  ASSERT_EQ(plan.shots.size(), 2u);
  EXPECT_EQ(plan.shots[0].shooter, 2u);
  EXPECT_EQ(plan.shots[1].shooter, 4u);
  settings.shooters_per_round = 3;
  const RoundPlan three = ProgressiveSolver(scene, settings).PlanRound(1024);
  ASSERT_EQ(three.shots.size(), 3u);
  EXPECT_EQ(three.shots[2].shooter, 5u);
  settings.shooters_per_round = 0;
  EXPECT_EQ(ProgressiveSolver(scene, settings).PlanRound(1024).shots.size(), 4u);
}

}  // namespace
}  // namespace radfarm
