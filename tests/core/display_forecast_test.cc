// The display's rays forecast before it is planned (core/display_budget.h), for the ETA.
#include <gtest/gtest.h>

#include "core/direct_light.h"
#include "core/display_budget.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

TEST(DisplayForecastTest, ADisplayWithRaysIsForecastFromTheStartsShadowRays) {
  const PatchScene scene = testing::LightsOverFloor(2);
  const SolverSettings settings = testing::Gathering(2048);
  ASSERT_TRUE(DisplayCastsRays(scene, settings));
  EXPECT_EQ(DisplayRaysForecast(scene, settings, 1'000'000), 6'000'000u);
  // No start on this mesh (its shadow rays unknown or none): nothing to forecast from.
  EXPECT_EQ(DisplayRaysForecast(scene, settings, 0), 0u);
}

TEST(DisplayForecastTest, ADisplayWithoutRaysCostsNothing) {
  const PatchScene scene =
      testing::LightsOverFloor(9);  // the emitters shoot: the display averages the patches
  const SolverSettings settings = testing::Gathering(2048);
  ASSERT_FALSE(DisplayCastsRays(scene, settings));
  EXPECT_EQ(DisplayRaysForecast(scene, settings, 1'000'000), 0u);
}

TEST(DisplayForecastTest, ABudgetCapsTheForecastAtTheDisplaysAllowance) {
  const PatchScene scene = testing::LightsOverFloor(1);
  SolverSettings settings = testing::Gathering(2048);
  settings.max_rays = 400'000'000;
  ASSERT_TRUE(DisplayCastsRays(scene, settings));
  EXPECT_EQ(DisplayRaysForecast(scene, settings, 1'000'000), 6'000'000u);
  EXPECT_EQ(DisplayRaysForecast(scene, settings, 100'000'000), DisplayRayAllowance(settings));
}

}  // namespace
}  // namespace radfarm
