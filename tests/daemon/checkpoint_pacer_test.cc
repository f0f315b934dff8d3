// CheckpointPacer: every round by default (the first round's too), never two at once, at most
// every min_seconds (the first too, from the first round), and written only once the job has run
// 1/share times as long as the last one took to write.
#include "daemon/checkpoint_pacer.h"

#include <gtest/gtest.h>

namespace radfarm::daemon {
namespace {

TEST(CheckpointPacerTest, WithoutLimitsEveryRoundCheckpointsOnceTheLastIsWritten) {
  CheckpointPacer pacer(0, 0);
  EXPECT_TRUE(pacer.Due(1, 1000));
  EXPECT_FALSE(pacer.Due(1, 1001)) << "the first is still being written";
  EXPECT_TRUE(pacer.Due(2, 1001)) << "another job has its own";
  pacer.Written(1, 30);
  EXPECT_TRUE(pacer.Due(1, 1002));
}

TEST(CheckpointPacerTest, ASlowWriteMakesTheNextWaitUntilItIsAShareOfTheTime) {
  CheckpointPacer pacer(0, 0.05);
  ASSERT_TRUE(pacer.Due(1, 0));
  pacer.Written(1, 2.0);  // 2 s to write: the next after 40 s of the job
  EXPECT_FALSE(pacer.Due(1, 6000));
  EXPECT_FALSE(pacer.Due(1, 39999));
  ASSERT_TRUE(pacer.Due(1, 40000));
  pacer.Written(1, 0.001);  // a quick one: the next at once (1 ms needs 20 ms)
  EXPECT_FALSE(pacer.Due(1, 40019));
  EXPECT_TRUE(pacer.Due(1, 40020));
}

TEST(CheckpointPacerTest, MinSecondsAndTheShareBothHold) {
  CheckpointPacer pacer(10, 0.05);
  EXPECT_FALSE(pacer.Due(1, 0)) << "the first round starts the pace";
  EXPECT_FALSE(pacer.Due(1, 9999));
  ASSERT_TRUE(pacer.Due(1, 10000));
  pacer.Written(1, 1.0);  // the share wants 20 s, min_seconds 10
  EXPECT_FALSE(pacer.Due(1, 20000));
  EXPECT_TRUE(pacer.Due(1, 30000));
  pacer.Written(1, 0.1);  // the share wants 2 s, min_seconds 10
  EXPECT_FALSE(pacer.Due(1, 35000));
  EXPECT_TRUE(pacer.Due(1, 40000));
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
}  // namespace radfarm::daemon
