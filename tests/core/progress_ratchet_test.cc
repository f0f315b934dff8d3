// ProgressRatchet: what a person is shown never goes back, and stays within 0..1.
#include "core/progress_ratchet.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(ProgressRatchetTest, ShowsTheHighestEstimateSeenWithinZeroToOne) {
  ProgressRatchet ratchet;
  EXPECT_EQ(ratchet.shown(), 0);
  EXPECT_DOUBLE_EQ(ratchet.Show(0.3), 0.3);
  EXPECT_DOUBLE_EQ(ratchet.Show(0.08), 0.3);  // a refit fell: held
  EXPECT_DOUBLE_EQ(ratchet.Show(0.5), 0.5);   // caught up: moves on
  EXPECT_DOUBLE_EQ(ratchet.Show(-1), 0.5);
  EXPECT_DOUBLE_EQ(ratchet.Show(1.5), 1.0);
  EXPECT_DOUBLE_EQ(ratchet.shown(), 1.0);
}

}  // namespace
}  // namespace radfarm
