// CheckpointPacer: every round by default (the first round's too), never two at once, at most
// every min_seconds (the first too, from the first round), and only while all of a job's
// checkpoints, the next priced as the last, take at most a share of its time.
#include "store/checkpoint_pacer.h"

#include <gtest/gtest.h>

namespace radfarm::store {
namespace {

TEST(CheckpointPacerTest, WithoutLimitsEveryRoundCheckpointsOnceTheLastIsWritten) {
  CheckpointPacer pacer(0, 0);
  EXPECT_TRUE(pacer.Due(1, 1000));
  EXPECT_FALSE(pacer.Due(1, 1001)) << "the first is still being written";
  EXPECT_TRUE(pacer.Due(2, 1001)) << "another job has its own";
  pacer.Written(1, 30);
  EXPECT_TRUE(pacer.Due(1, 1002));
}

TEST(CheckpointPacerTest, SlowWritesWaitUntilAllOfThemAreAShareOfTheJobsTime) {
  CheckpointPacer pacer(0, 0.05);
  ASSERT_TRUE(pacer.Due(1, 0)) << "the first round's, its cost unknown";
  pacer.Written(1, 2.0);  // 2 s, and the next priced the same: 4 s are 5 % of 80 s
  EXPECT_FALSE(pacer.Due(1, 6000));
  EXPECT_FALSE(pacer.Due(1, 79999));
  ASSERT_TRUE(pacer.Due(1, 80000));
  pacer.Written(1, 2.0);  // 4 s spent, 2 more: 120 s
  EXPECT_FALSE(pacer.Due(1, 119999));
  ASSERT_TRUE(pacer.Due(1, 120000));
  pacer.Written(1, 0.001);  // quick now: 4.002 s need 80.04 s of the job, long past
  EXPECT_TRUE(pacer.Due(1, 120001));
}

TEST(CheckpointPacerTest, MinSecondsAndTheShareBothHold) {
  CheckpointPacer pacer(10, 0.05);
  EXPECT_FALSE(pacer.Due(1, 0)) << "the first round starts the pace";
  EXPECT_FALSE(pacer.Due(1, 9999));
  ASSERT_TRUE(pacer.Due(1, 10000));
  pacer.Written(1, 1.0);  // the share wants 40 s of the job, min_seconds 10 since the last
  EXPECT_FALSE(pacer.Due(1, 20000));
  EXPECT_FALSE(pacer.Due(1, 39999));
  ASSERT_TRUE(pacer.Due(1, 40000));
  pacer.Written(1, 0.1);  // the share wants 24 s (met), min_seconds 10 since the last
  EXPECT_FALSE(pacer.Due(1, 45000));
  EXPECT_TRUE(pacer.Due(1, 50000));
}

TEST(CheckpointPacerTest, AFailedWriteDoesNotHoldTheNextBack) {
  CheckpointPacer pacer(0, 0.05);
  ASSERT_TRUE(pacer.Due(1, 0));
  pacer.Written(1, 0);
  EXPECT_TRUE(pacer.Due(1, 1));
}

TEST(CheckpointPacerTest, AForgottenJobStartsAfreshButWaitsForTheWriteInFlight) {
  CheckpointPacer pacer(0, 0.05);
  ASSERT_TRUE(pacer.Due(1, 0));
  pacer.Forget(1);  // paused while its checkpoint is written
  EXPECT_FALSE(pacer.Due(1, 100000));
  pacer.Written(1, 5.0);  // the old runner's: it no longer sets the pace
  EXPECT_TRUE(pacer.Due(1, 100001));
  pacer.Written(1, 0.5);
  pacer.Forget(1);
  EXPECT_TRUE(pacer.Due(1, 100002)) << "nothing in flight: forgotten entirely";
}

}  // namespace
}  // namespace radfarm::store
