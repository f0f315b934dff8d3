#include "core/solve_control.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

// A round that fits with the rounds after it is not paced.
TEST(PacedRoundCapTest, NoCapWhereTheRoundsToComeFit) {
  // 1 M rays shoot 0.4 of the emitted power; a carry of 0.5 brings the whole unshot (0.4) and what
  // it carries back to 0.8 down to the tolerance: about 2 M rays in all.
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0.001, 0.5, 2000000), 0u);
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0.001, 0.5, 0), 0u);       // no budget
  EXPECT_EQ(PacedRoundCap(0, 0.4, 0.4, 0.001, 0.5, 1000), 0u);          // nothing to shoot
  EXPECT_EQ(PacedRoundCap(1000000, 0.0, 0.4, 0.001, 0.5, 1000), 0u);    // no power
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.001, 0.001, 0.5, 1000), 0u);  // converged
}

// Where they do not fit, the round gets its share of what is left: every round at the same
// fraction of its full rays.
TEST(PacedRoundCapTest, TheRoundGetsItsShareOfWhatIsLeft) {
  // Needed: 1 M x (0.4 - 0) / 0.4 / (1 - 0.5) = 2 M; 500,000 left: a quarter.
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0, 0.5, 500000), 250000u);
  // A round that shoots half the unshot (shooters_per_round) is half of what the rest needs too.
  EXPECT_EQ(PacedRoundCap(1000000, 0.2, 0.4, 0, 0.5, 500000), 125000u);
  // No carry: this round's rays and the rest's in proportion to the unshot.
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0, 0, 500000), 500000u);
  // A carry near 1 is held to 0.95 (twenty times the unshot at most).
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0, 1.0, 1000000), 50000u);
  // At least a ray, however little is left.
  EXPECT_EQ(PacedRoundCap(1000000, 0.4, 0.4, 0, 0.5, 1), 1u);
}

}  // namespace
}  // namespace radfarm
