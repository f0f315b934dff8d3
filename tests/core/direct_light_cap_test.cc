// core/direct_light.h: a light of many patches gets a capped number of shadow rays
// (DirectLightRaysPerLight), drawn among its patches by their share of its light; and the rule
// that decides when a solve starts from the emitters' direct light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "core/direct_light.h"
#include "core/display_budget.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::Gathering;

// The unit square 1 above z = 0, facing down, emitting 1, as an n x n grid of patches.
PatchScene GridLight(int n) {
  PatchScene scene;
  testing::AddQuadGrid({-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}, n,
                       testing::Surface{{}, {1, 1, 1}, 0}, &scene);
  return scene;
}

// A grey floor under it, in n x n patches over [-2, 2]^2.
void AddFloor(int n, PatchScene* scene) {
  testing::AddQuadGrid({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, n,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, scene);
}

TEST(DirectLightCapTest, AnUnoccludedLightIsExactWithFewRays) {
  const PatchScene scene = GridLight(8);  // 64 patches, 4 rays
  const RayCaster caster(scene);
  const DirectLight all(scene, caster, 1);
  const DirectLight capped(scene, caster, 1, true, kExactLights, kLightCut, 4);
  for (const Vec3& x : {Vec3{0, 0, 0}, Vec3{0.5, 0.5, 0}, Vec3{1.3, -0.2, 0.4}}) {
    const Rgb a = all.EmitterIrradiance(x, {0, 0, 1}, 9);
    const Rgb c = capped.EmitterIrradiance(x, {0, 0, 1}, 9);
    EXPECT_GT(a.g, 0);
    EXPECT_NEAR(c.g, a.g, 1e-12 * a.g) << x.x;
  }
}

// Half the light hidden behind a blade: each capped estimate is a multiple of a quarter of the
// kernel-weighted share, and over many keys the mean meets the patch-by-patch sum.
TEST(DirectLightCapTest, APenumbraIsEstimatedWithoutBias) {
  PatchScene scene = GridLight(8);
  testing::AddQuadGrid({-2, -2, 0.5}, {-2, 2, 0.5}, {0, 2, 0.5}, {0, -2, 0.5}, 1,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 2}, &scene);
  const RayCaster caster(scene);
  const DirectLight all(scene, caster, 1024);  // 4 x 4 rays per patch
  const DirectLight capped(scene, caster, 1, true, kExactLights, kLightCut, 4);
  const Vec3 x{0.1, 0.2, 0}, n{0, 0, 1};
  double all_sum = 0, capped_sum = 0;
  bool varied = false;
  const double first = capped.EmitterIrradiance(x, n, 0).g;
  constexpr int kKeys = 4000;
  for (int key = 0; key < kKeys; ++key) {
    all_sum += all.EmitterIrradiance(x, n, key).g;
    const double c = capped.EmitterIrradiance(x, n, key).g;
    capped_sum += c;
    varied = varied || c != first;
  }
  EXPECT_TRUE(varied) << "the blade's edge crosses the light: some rays must be blocked";
  const double exact = all_sum / kKeys, mean = capped_sum / kKeys;
  EXPECT_GT(exact, 0);
  EXPECT_NEAR(mean, exact, 0.01 * exact);
}

TEST(DirectLightCapTest, TheStartCapsRaysWhenLightsAreFinelyMeshed) {
  PatchScene scene = GridLight(16);  // 256 emitter patches: more than 2048 / 16
  AddFloor(40, &scene);              // 1600 receivers
  const SolverSettings settings = Gathering(2048);
  EXPECT_TRUE(EmittersInDirectStart(scene, settings));
  EXPECT_EQ(DirectLightRaysPerLight(scene, settings), 128u) << "one light: 2048 / 16";
  EXPECT_EQ(DirectLightSections(scene, settings), 4u) << "floor(sqrt(2048 / (2 x 128)))";

  // Lights meshed coarsely enough keep a ray per patch, as before the cap.
  PatchScene coarse = GridLight(4);
  AddFloor(40, &coarse);
  EXPECT_TRUE(EmittersInDirectStart(coarse, settings));
  EXPECT_EQ(DirectLightRaysPerLight(coarse, settings), 0u);

  // A furnace: every patch emits, and the emitters shoot.
  PatchScene furnace = GridLight(16);
  EXPECT_FALSE(EmittersInDirectStart(furnace, settings));
  EXPECT_EQ(DirectLightRaysPerLight(furnace, settings), 0u);
  // Too few gather rays for kMinCappedLightRays per light and 16 points: the emitters shoot.
  EXPECT_FALSE(EmittersInDirectStart(scene, Gathering(128)));
  EXPECT_TRUE(EmittersInDirectStart(scene, Gathering(256)));
  EXPECT_EQ(DirectLightRaysPerLight(scene, Gathering(256)), kMinCappedLightRays);
}

// Under a budget the start fits a quarter of it (the budget holds from the first second):
// fewer points per patch first, then fewer rays per light, then the emitters shoot.
TEST(DirectLightCapTest, ABudgetFitsTheStartToAQuarterOfIt) {
  PatchScene scene = GridLight(16);  // one light of 256 patches
  AddFloor(40, &scene);
  const uint64_t patches = scene.patches.size();
  SolverSettings settings = Gathering(2048);
  const auto plan = [&](uint64_t max_rays) {
    settings.max_rays = max_rays;
    return std::tuple(EmittersInDirectStart(scene, settings), DirectLightSections(scene, settings),
                      DirectLightRaysPerLight(scene, settings));
  };
  EXPECT_EQ(StartRayAllowance(settings), 0u) << "no budget";
  // 4 x 4 points of 128 rays a patch fit a quarter: as without a budget.
  EXPECT_EQ(plan(4 * patches * 16 * 128), std::tuple(true, 4u, 128u));
  EXPECT_EQ(StartRayAllowance(settings), patches * 16 * 128);
  EXPECT_EQ(plan(4 * patches * 16 * 128 - 4), std::tuple(true, 3u, 128u));
  EXPECT_EQ(plan(4 * patches * 4 * 128), std::tuple(true, 2u, 128u));
  EXPECT_EQ(plan(4 * patches * 128), std::tuple(true, 1u, 128u));
  EXPECT_EQ(plan(4 * patches * 64), std::tuple(true, 1u, 64u)) << "one point, fewer rays";
  EXPECT_EQ(plan(4 * patches * kMinCappedLightRays), std::tuple(true, 1u, kMinCappedLightRays));
  EXPECT_EQ(plan(4 * patches * kMinCappedLightRays - 4), std::tuple(false, 0u, 0u))
      << "too little for 16 rays a point: the emitters shoot";
  // A time budget plans at kStartShadowRaysPerSecond: the same on every machine.
  settings.max_rays = 0;
  settings.max_seconds = double(patches * 64) * kStartBudgetShare / kStartShadowRaysPerSecond;
  EXPECT_EQ(StartRayAllowance(settings), patches * 64);
  EXPECT_EQ(DirectLightRaysPerLight(scene, settings), 64u);
  settings.max_rays = 4 * patches * 32;  // both: the smaller allowance
  EXPECT_EQ(DirectLightRaysPerLight(scene, settings), 32u);

  // The start casts what its plan says at most, counted the same whatever the threads.
  settings.max_seconds = 0;
  settings.max_rays = 4 * patches * 4 * 128;
  for (unsigned threads : {1u, 3u}) {
    settings.threads = threads;
    uint64_t rays = 0;
    const std::vector<Rgb> start = StartingDirectLight(scene, settings, nullptr, &rays);
    EXPECT_EQ(start.size(), patches);
    EXPECT_GT(rays, patches * 4 * 128 / 2) << "most floor points see the light";
    EXPECT_LE(rays, StartRayAllowance(settings));
    uint64_t again = 0;
    EXPECT_EQ(PatchDirectLight(scene, 2, settings.seed, 2, true, nullptr, 128, &again), start);
    EXPECT_EQ(again, rays) << threads;
  }
}

// A budget keeps a quarter for the display after the solve (core/display_budget.h), where a
// display with rays follows (a direct light to start from); the rounds stop at the rest.
TEST(DirectLightCapTest, ABudgetKeepsAQuarterForTheDisplay) {
  PatchScene scene = GridLight(16);
  AddFloor(40, &scene);
  SolverSettings settings = Gathering(2048);
  EXPECT_EQ(DisplayRayAllowance(settings), 0u) << "no budget";
  EXPECT_EQ(SolveBudget(scene, settings).max_rays, 0u);
  settings.max_rays = 4000002;
  EXPECT_TRUE(DisplayCastsRays(scene, settings));
  EXPECT_EQ(DisplayRayAllowance(settings), 1000000u);
  EXPECT_EQ(SolveBudget(scene, settings).max_rays, 3000002u);
  // A budget of fewer rays than the share is still a budget: one ray each, not none.
  settings.max_rays = 3;
  EXPECT_EQ(DisplayRayAllowance(settings), 1u);
  EXPECT_EQ(StartRayAllowance(settings), 1u);
  settings.max_rays = 4000002;
  settings.max_seconds = 8;  // both: the smaller allowance; the solve's time less what follows
  EXPECT_EQ(DisplayRayAllowance(settings),
            std::min<uint64_t>(1000000, uint64_t(8 * kDisplayRaysPerSecond / 4)));
  EXPECT_DOUBLE_EQ(SolveBudget(scene, settings).max_seconds,
                   8 - AfterSolveSeconds(scene, settings));
  // No direct light to start from (the emitters shoot: a furnace): the display averages, the
  // solve keeps every ray, and the time but for the outputs.
  const PatchScene furnace = GridLight(16);
  EXPECT_FALSE(DisplayCastsRays(furnace, settings));
  EXPECT_EQ(SolveBudget(furnace, settings).max_rays, 4000002u);
  EXPECT_DOUBLE_EQ(SolveBudget(furnace, settings).max_seconds,
                   8 - AfterSolveSeconds(furnace, settings));
}

// A time budget keeps the time what follows the solve takes (on a big scene `--seconds 5` ended
// after 6.3 s): the display's rays, where it casts any, and the display's work at its points and
// the outputs, growing with the patches. One that leaves the rounds nothing is still a budget: the
// solve is its start.
TEST(DirectLightCapTest, ATimeBudgetKeepsTheTimeAfterTheSolve) {
  PatchScene small = GridLight(4);
  AddFloor(10, &small);
  PatchScene big = GridLight(16);
  AddFloor(300, &big);
  ASSERT_GT(big.patches.size(), 50 * small.patches.size());
  SolverSettings settings = Gathering(2048);
  settings.max_seconds = 5;
  settings.threads = kAfterSolveThreads;
  ASSERT_TRUE(DisplayCastsRays(small, settings));
  EXPECT_DOUBLE_EQ(AfterSolveSeconds(small, settings),
                   double(DisplayRayAllowance(settings)) / kDisplayReserveRaysPerSecond +
                       kAfterSolveSeconds +
                       kAfterSolveSecondsPerPatch * double(small.patches.size()));
  EXPECT_GT(AfterSolveSeconds(big, settings), AfterSolveSeconds(small, settings) + 1);
  EXPECT_LT(SolveBudget(big, settings).max_seconds, SolveBudget(small, settings).max_seconds);
  EXPECT_EQ(SolveBudget(big, settings).max_rays, 0u) << "a time budget only";
  // No display rays (the furnace: the emitters shoot), no time for them.
  const PatchScene furnace = GridLight(16);
  EXPECT_DOUBLE_EQ(
      AfterSolveSeconds(furnace, settings),
      kAfterSolveSeconds + kAfterSolveSecondsPerPatch * double(furnace.patches.size()));
  // One thread: what runs on the threads takes twice as long; more threads are not counted on.
  SolverSettings one = settings, many = settings;
  one.threads = 1;
  many.threads = 4 * kAfterSolveThreads;
  EXPECT_DOUBLE_EQ(AfterSolveSeconds(big, one) - kAfterSolveSeconds,
                   2 * (AfterSolveSeconds(big, settings) - kAfterSolveSeconds));
  EXPECT_DOUBLE_EQ(AfterSolveSeconds(big, many), AfterSolveSeconds(big, settings));
  settings.max_seconds = 0.5;
  EXPECT_EQ(SolveBudget(big, settings).max_seconds, kMinSolveSeconds);
  EXPECT_GT(SolveBudget(big, settings).max_seconds, 0) << "still a budget";
}

// `count` lights of 36 patches each (distinct surfaces) over a 60 x 60 floor.
PatchScene FinelyMeshedLights(int count) {
  PatchScene scene;
  for (int i = 0; i < count; ++i) {
    const double x = 2.0 * i;
    testing::AddQuadGrid({x, 0, 1}, {x, 1, 1}, {x + 1, 1, 1}, {x + 1, 0, 1}, 6,
                         testing::Surface{{}, {1, 1, 1}, uint32_t(10 + i)}, &scene);
  }
  AddFloor(60, &scene);
  return scene;
}

// Eight lights get 16 rays each; nine would get fewer, so their emitters shoot, as in a building
// of many rooms.
TEST(DirectLightCapTest, ManyFinelyMeshedLightsShoot) {
  const SolverSettings settings = Gathering(2048);
  const PatchScene eight = FinelyMeshedLights(8);
  EXPECT_TRUE(EmittersInDirectStart(eight, settings));
  EXPECT_EQ(DirectLightRaysPerLight(eight, settings), 16u) << "2048 / (16 x 8)";
  const PatchScene nine = FinelyMeshedLights(9);
  EXPECT_FALSE(EmittersInDirectStart(nine, settings));
  EXPECT_EQ(DirectLightRaysPerLight(nine, settings), 0u);
  EXPECT_EQ(DirectLightRaysPerLight(nine, Gathering(2304)), 16u) << "2304 / (16 x 9)";
}

TEST(DirectLightCapTest, ThePatchStartWithTheCapIsAPureFunctionAndCloseToTheFullOne) {
  PatchScene scene = GridLight(16);
  AddFloor(12, &scene);
  const std::vector<Rgb> full = PatchDirectLight(scene, 4, 3, 2);
  const std::vector<Rgb> one = PatchDirectLight(scene, 4, 3, 1, true, nullptr, 8);
  const std::vector<Rgb> two = PatchDirectLight(scene, 4, 3, 2, true, nullptr, 8);
  EXPECT_TRUE(testing::BitIdentical(one, two));
  // Nothing shadows the floor: the cap changes nothing but rounding.
  for (size_t i = 256; i < scene.patches.size(); ++i) {
    EXPECT_NEAR(one[i].g, full[i].g, 1e-12 * full[i].g + 1e-300) << i;
  }
}

}  // namespace
}  // namespace radfarm
