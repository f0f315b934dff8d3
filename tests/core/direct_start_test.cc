// The direct-light start as work cut by patch (core/direct_start.h): pieces traced anywhere, on any
// threads, put together give PatchDirectLight's bits, its punctual power and its shadow rays (the
// agents' path to them: tests/display/point_context_test.cc); a solver given a source of its start
// is the solver that traced its own.
#include "core/direct_start.h"

#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "core/direct_light.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

constexpr StartWork kWork{4, 99, true, 8};

TEST(DirectStartTest, PiecesOnAnyThreadsGiveThePatchDirectLight) {
  const PatchScene scene = testing::LightsAndLampOverFloor();
  double power = 0;
  uint64_t rays = 0;
  const std::vector<Rgb> whole = PatchDirectLight(
      scene, kWork.sections, kWork.seed, 2, kWork.emitters, &power, kWork.rays_per_light, &rays);
  const RayCaster caster(scene);
  const DirectLight direct = StartDirectLight(scene, caster, kWork);
  const size_t n = scene.patches.size();
  PatchStartValues pieces;
  const size_t cuts[] = {0, 7, n / 2, n};
  for (size_t k = 0; k + 1 < std::size(cuts); ++k) {
    AppendStartValues(TraceStartPatches(scene, direct, caster, kWork, cuts[k], cuts[k + 1], k + 1),
                      &pieces);
  }
  ASSERT_EQ(pieces.punctual.size(), n) << "the lamp's share per patch";
  const StartLight start = StartLightOf(scene, std::move(pieces));
  EXPECT_TRUE(testing::BitIdentical(start.direct, whole));
  EXPECT_EQ(start.punctual_power, power);
  EXPECT_GT(power, 0);
  EXPECT_EQ(start.shadow_rays, rays);
  EXPECT_GT(rays, 0u);
}

TEST(DirectStartTest, AStartSourceGivesTheSolverItsStart) {
  const PatchScene scene = testing::LightsOverFloor(2);
  const SolverSettings settings = testing::Gathering(2048);
  const ProgressiveSolver here(scene, settings);
  ASSERT_FALSE(here.direct_light().empty());
  int calls = 0;
  const StartLightSource source = [&](const PatchScene& s, const StartWork& work) {
    ++calls;
    EXPECT_EQ(std::optional<StartWork>(work), StartWorkOf(s, settings));
    const RayCaster caster(s);
    const DirectLight direct = StartDirectLight(s, caster, work);
    return StartLightOf(s, TraceStartPatches(s, direct, caster, work, 0, s.patches.size(), 1));
  };
  const ProgressiveSolver elsewhere(scene, settings, source);
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(testing::BitIdentical(elsewhere.direct_light(), here.direct_light()));
  EXPECT_TRUE(testing::BitIdentical(elsewhere.radiosity(), here.radiosity()));
  EXPECT_EQ(elsewhere.start_rays(), here.start_rays());
  EXPECT_EQ(elsewhere.energy().emitted, here.energy().emitted);
}

}  // namespace
}  // namespace radfarm
