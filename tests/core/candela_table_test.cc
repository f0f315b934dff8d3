// core/candela_table.h: interpolation between the measured angles, the LM-63 symmetries and the
// flux a table emits, against values worked by hand.
#include "core/candela_table.h"

#include <gtest/gtest.h>

#include <numbers>

namespace radfarm {
namespace {

TEST(CandelaTable, InterpolatesBilinearlyAndIsDarkOutsideTheVerticalAngles) {
  const CandelaTable table{{0, 60}, {0, 90}, {100, 40, 300, 0}};
  ASSERT_EQ(CandelaTableProblem(table), "");
  EXPECT_DOUBLE_EQ(CandelaAt(table, 0, 0), 100);
  EXPECT_DOUBLE_EQ(CandelaAt(table, 30, 0), 70);
  EXPECT_DOUBLE_EQ(CandelaAt(table, 0, 45), 200);
  EXPECT_DOUBLE_EQ(CandelaAt(table, 30, 45), 0.5 * 70 + 0.5 * 150);
  EXPECT_DOUBLE_EQ(CandelaAt(table, 61, 0), 0);
  EXPECT_DOUBLE_EQ(CandelaAt(table, 180, 0), 0);
}

TEST(CandelaTable, UnfoldsEachSymmetryOfLm63) {
  // Rotational: one plane serves every phi.
  const CandelaTable round{{0, 90}, {0}, {100, 0}};
  EXPECT_DOUBLE_EQ(CandelaAt(round, 45, 217), 50);
  // Quadrant: 0..90 mirrored into the other three.
  const CandelaTable quadrant{{0}, {0, 90}, {10, 100}};
  EXPECT_DOUBLE_EQ(CandelaAt(quadrant, 0, 30), 40);
  EXPECT_DOUBLE_EQ(CandelaAt(quadrant, 0, 150), 40);
  EXPECT_DOUBLE_EQ(CandelaAt(quadrant, 0, 210), 40);
  EXPECT_DOUBLE_EQ(CandelaAt(quadrant, 0, -30), 40);
  // Bilateral about the 0-180 plane.
  const CandelaTable bilateral{{0}, {0, 180}, {0, 180}};
  EXPECT_DOUBLE_EQ(CandelaAt(bilateral, 0, 200), 160);
  // Bilateral about the 90-270 plane.
  const CandelaTable side{{0}, {90, 270}, {0, 180}};
  EXPECT_DOUBLE_EQ(CandelaAt(side, 0, 30), 60);
  EXPECT_DOUBLE_EQ(CandelaAt(side, 0, 300), 150);
  // Full: 360 closes the circle on 0.
  const CandelaTable full{{0}, {0, 180, 360}, {0, 180, 0}};
  EXPECT_DOUBLE_EQ(CandelaAt(full, 0, 270), 90);
  EXPECT_DOUBLE_EQ(CandelaAt(full, 0, 720 + 90), 90);
}

TEST(CandelaTable, ItsLumensAreTheIntegralOverTheSphere) {
  const CandelaTable isotropic{{0, 180}, {0}, {100, 100}};
  EXPECT_NEAR(TableLumens(isotropic), 4 * std::numbers::pi * 100,
              4 * std::numbers::pi * 100 * 1e-5);
  // Only the lower hemisphere, linear in phi across the quadrant: the planes' mean, 200 cd, over
  // 2 pi steradians.
  const CandelaTable lower{{0, 90}, {0, 90}, {100, 100, 300, 300}};
  EXPECT_NEAR(TableLumens(lower), 2 * std::numbers::pi * 200, 2 * std::numbers::pi * 200 * 1e-4);
}

TEST(CandelaTable, NamesWhatIsWrong) {
  EXPECT_EQ(CandelaTableProblem({{}, {0}, {}}),
            "the table has no vertical or no horizontal angles");
  EXPECT_EQ(CandelaTableProblem({{0, 0}, {0}, {1, 1}}),
            "the vertical angles are not strictly increasing");
  EXPECT_EQ(CandelaTableProblem({{0, 190}, {0}, {1, 1}}),
            "the vertical angles are not within 0 to 180");
  EXPECT_EQ(CandelaTableProblem({{0}, {0, 45}, {1, 1}}),
            "the horizontal angles are not 0 alone, 0 to 90, 0 to 180, 90 to 270 or 0 to 360");
  EXPECT_EQ(CandelaTableProblem({{0}, {0}, {1, 1}}), "the table has 2 candela values, not 1");
  EXPECT_EQ(CandelaTableProblem({{0}, {0}, {-1}}), "a candela value is negative or not finite");
}

}  // namespace
}  // namespace radfarm
