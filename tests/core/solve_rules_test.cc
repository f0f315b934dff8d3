// The rules that decide a solve's direct-light start and its display, in words: a scene of many
// lights (a 4 x 4 building, an office floor) got no start and the patches' averages for a display
// with no word, so it finished before a smaller scene and looked alike at a glance.
#include "core/solve_rules.h"

#include <gtest/gtest.h>

#include "core/direct_light.h"
#include "core/display_budget.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

TEST(SolveRulesTest, AFewLightsGetTheStartAndADisplayAtItsPoints) {
  const PatchScene scene = testing::LightsOverFloor(8);
  const SolverSettings settings = testing::Gathering(2048);
  const RuleOutcome start = DirectStartRule(scene, settings);
  EXPECT_TRUE(start.used);
  EXPECT_EQ(start.why,
            "from the direct light of 288 emitter patches, 16 shadow rays per light, at 4 x 4 "
            "points per patch");
  const RuleOutcome display = DisplayRule(scene, settings);
  EXPECT_TRUE(display.used);
  EXPECT_EQ(display.used, DisplayCastsRays(scene, settings));
  EXPECT_EQ(display.why.rfind("at its own points: ", 0), 0u) << display.why;
}

TEST(SolveRulesTest, ManyLightsSayWhyTheyShootAndTheDisplayAverages) {
  const PatchScene scene = testing::LightsOverFloor(9);
  const SolverSettings settings = testing::Gathering(2048);
  const RuleOutcome start = DirectStartRule(scene, settings);
  EXPECT_FALSE(start.used);
  EXPECT_EQ(start.used, DirectLightSections(scene, settings) > 0);
  EXPECT_EQ(start.why,
            "not used: 9 lights per point need at least 16 points x 16 shadow rays each, more "
            "than the gather's 2048 rays (at most 8 lights); the emitter patches shoot their "
            "light in the rounds instead");
  const RuleOutcome display = DisplayRule(scene, settings);
  EXPECT_FALSE(display.used);
  EXPECT_EQ(display.used, DisplayCastsRays(scene, settings));
  EXPECT_EQ(display.why,
            "the patches' averages, no rays of its own: the solve does not start from the direct "
            "light (9 lights per point need at least 16 points x 16 shadow rays each, more than "
            "the gather's 2048 rays (at most 8 lights); the emitter patches shoot their light in "
            "the rounds instead)");
}

TEST(SolveRulesTest, EachOtherReasonIsNamed) {
  // A furnace: every patch emits.
  PatchScene furnace;
  testing::AddQuadGrid({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 16,
                       testing::Surface{{0.5, 0.5, 0.5}, {1, 1, 1}, 0}, &furnace);
  EXPECT_NE(DirectStartRule(furnace, testing::Gathering(2048))
                .why.find("256 of the 256 patches emit, more than a quarter"),
            std::string::npos);
  // No gather, no start.
  SolverSettings no_gather = testing::Gathering(2048);
  no_gather.gather_rays = 0;
  EXPECT_NE(
      DirectStartRule(testing::LightsOverFloor(1), no_gather).why.find("the final gather is off"),
      std::string::npos);
  // A ray budget too small for 16 rays per light at a point a patch.
  SolverSettings budget = testing::Gathering(2048);
  budget.max_rays = 4000;
  const RuleOutcome tight = DirectStartRule(testing::LightsOverFloor(8), budget);
  EXPECT_NE(tight.why.find("the budget's share for it (1000 shadow rays)"), std::string::npos)
      << tight.why;
}

}  // namespace
}  // namespace radfarm
