// core/direct_light.h: the solver's starting direct light as a pure function of scene and settings
// (the display and `radfarm fetch` recompute it), and the direct light at points against the
// closed form.
#include "core/direct_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/progressive_solver.h"
#include "tests/core/test_scenes.h"

namespace radfarm {
namespace {

using testing::BitIdentical;
using testing::Gathering;
using testing::LitBox;

TEST(DirectLightTest, SectionsFollowTheGatherRays) {
  const PatchScene scene = LitBox();  // one emitter patch
  EXPECT_EQ(DirectLightSections(scene, Gathering(2048)), 16u) << "at most 16 x 16";
  EXPECT_EQ(DirectLightSections(scene, Gathering(64)), 5u) << "floor(sqrt(64 / 2))";
  EXPECT_EQ(DirectLightSections(scene, Gathering(16)), 4u) << "at least 4 x 4";
  EXPECT_EQ(DirectLightSections(scene, Gathering(8)), 0u) << "16 rays per emitter patch or none";
  EXPECT_EQ(DirectLightSections(scene, Gathering(0)), 0u) << "no gather, no direct-light start";
  SolverSettings grid = Gathering(2048);
  grid.sampler = SamplerKind::kGrid;
  EXPECT_EQ(DirectLightSections(scene, grid), 0u) << "the grid never gathers";
  PatchScene dark = scene;
  for (Patch& p : dark.patches) p.emission = {};
  EXPECT_EQ(DirectLightSections(dark, Gathering(2048)), 0u);
}

// `radfarm fetch` has only the values and recomputes the direct light the display needs: it must
// be the solver's start to the bit, whatever the threads.
TEST(DirectLightTest, StartingDirectLightIsTheSolversStart) {
  const PatchScene scene = LitBox();
  for (uint32_t gather_rays : {2048u, 64u, 8u}) {
    SolverSettings settings = Gathering(gather_rays);
    const ProgressiveSolver solver(scene, settings);
    settings.threads = 1;
    const std::vector<Rgb> again = StartingDirectLight(scene, settings);
    EXPECT_EQ(again.empty(), gather_rays == 8) << gather_rays;
    EXPECT_TRUE(BitIdentical(solver.direct_light(), again)) << gather_rays;
  }
}

// The unit square 1 above the plane z = 0, facing down, emitting 1; nothing else.
PatchScene SquareLight() {
  PatchScene scene;
  testing::AddQuadGrid({-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}, 2,
                       testing::Surface{{}, {1, 1, 1}, 0}, &scene);
  return scene;
}

TEST(DirectLightTest, PointsMatchTheClosedFormUnoccludedAndIgnoreThreads) {
  const PatchScene scene = SquareLight();
  const std::vector<ReceiverPoint> points = {
      {{0, 0, 0}, {0, 0, 1}},        // under the centre
      {{0.5, 0.5, 0}, {0, 0, 1}},    // under a corner
      {{0, 0, 2}, {0, 0, 1}},        // above the light: sees its back
      {{0.25, 0, 0.5}, {0, 0, -1}},  // facing away
  };
  const std::vector<Rgb> one = PointsDirectLight(scene, points, 7, 1);
  const std::vector<Rgb> three = PointsDirectLight(scene, points, 7, 3);
  EXPECT_TRUE(BitIdentical(one, three));
  ASSERT_EQ(one.size(), points.size());
  EXPECT_NEAR(one[0].g, 4 * testing::CornerRectangle(0.5, 0.5), 1e-9);
  EXPECT_NEAR(one[0].g, 0.2394564705, 1e-9);  // Howell's catalogue, C-11
  EXPECT_NEAR(one[1].g, testing::CornerRectangle(1, 1), 1e-9);
  EXPECT_EQ(one[2], Rgb{});
  EXPECT_EQ(one[3], Rgb{});
  EXPECT_TRUE(PointsDirectLight(scene, {}, 7, 2).empty());
}

// An occluder between the point and the light: the shadow rays say so.
TEST(DirectLightTest, PointsInAnUmbraGetNothing) {
  PatchScene scene = SquareLight();
  testing::AddQuadGrid({-2, -2, 0.5}, {-2, 2, 0.5}, {2, 2, 0.5}, {2, -2, 0.5}, 1,
                       testing::Surface{{0.5, 0.5, 0.5}, {}, 1}, &scene);
  const std::vector<Rgb> e = PointsDirectLight(scene, {{{0, 0, 0}, {0, 0, 1}}}, 7, 2);
  EXPECT_EQ(e[0], Rgb{});
}

}  // namespace
}  // namespace radfarm
