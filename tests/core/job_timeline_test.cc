// A job's timeline (core/job_timeline.h): one entry per phase and place, summed, in order.
#include "core/job_timeline.h"

#include <gtest/gtest.h>

namespace radfarm {
namespace {

TEST(JobTimelineTest, EntriesArePerPhaseAndPlaceInTheOrderFirstMet) {
  JobTimeline t;
  AddToTimeline(&t, JobPhase::kMeshing, kRanOnMaster, 1.0, 0.5);
  AddToTimeline(&t, JobPhase::kRounds, kRanOnMaster, 2.0, 0.25);
  AddToTimeline(&t, JobPhase::kRounds, kRanOnAgents, 0, 8.0);
  AddToTimeline(&t, JobPhase::kRounds, kRanOnMaster, 3.0, 0.5);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0], (TimelineEntry{JobPhase::kMeshing, "master", 1.0, 0.5}));
  EXPECT_EQ(t[1], (TimelineEntry{JobPhase::kRounds, "master", 5.0, 0.75}));
  EXPECT_EQ(t[2], (TimelineEntry{JobPhase::kRounds, "agents", 0, 8.0}));
  EXPECT_EQ(TimelineLine(t),
            "meshing 1.0 s (CPU 0.5 s), rounds 5.0 s (CPU: master 0.8 s, agents 8.0 s)");
  EXPECT_EQ(TimelineLine({}), "");
}

TEST(JobTimelineTest, EveryPhaseHasAName) {
  for (JobPhase p : {JobPhase::kMeshing, JobPhase::kDirectLight, JobPhase::kRounds,
                     JobPhase::kGather, JobPhase::kDisplay, JobPhase::kOutputs}) {
    EXPECT_NE(JobPhaseName(p), "?");
  }
  EXPECT_EQ(JobPhaseName(JobPhase::kDirectLight), "direct light");
}

}  // namespace
}  // namespace radfarm
