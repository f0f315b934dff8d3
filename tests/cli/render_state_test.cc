// RenderState (render --db): rounds saved while earlier checkpoints are still being written leave
// every round's row and, once finished, the last round's checkpoint, with its exact values.
#include "cli/render_state.h"

#include <gtest/gtest.h>

#include <cstring>

#include "input/scene_loader.h"
#include "job/job.h"
#include "testing/temp_dir.h"

namespace radfarm {
namespace {

codec::JobBundle CornellBundle() {
  Result<Job> job = LoadJob(RADFARM_SOURCE_DIR "/scenes/cornell-box.toml");
  EXPECT_TRUE(job.ok()) << job.error();
  Result<InputScene> scene = LoadObjScene(job->scene_path);
  EXPECT_TRUE(scene.ok()) << scene.error();
  return {*job, *scene};
}

// The state after round `round`: big enough (12 MB a checkpoint) that the writer is usually still
// busy when the next round is saved, so some checkpoints are left out.
SolveState StateAfter(uint32_t round) {
  SolveState s;
  s.round = round;
  s.rounds_done = round + 1;
  s.shooters = 7;
  s.totals.rays = 1000 * (round + 1);
  s.totals.seconds = 0.5 * (round + 1);
  for (size_t i = 0; i < 250000; ++i) {
    const double x = (round + 1.0) / (i + 3.0);
    s.radiosity.push_back(Rgb(x, -0.0, x * 1e-300));
    s.unshot.push_back(Rgb(x * 1e-3, 0, x));
  }
  s.energy = {10.0, 6.0, 1.0, 3.0 / (round + 1)};
  return s;
}

TEST(RenderStateTest, EveryRoundHasItsRowAndFinishWritesTheLastRoundsCheckpoint) {
  testing::TempDir dir;
  const std::string db = dir.File("render.db");
  constexpr uint32_t kRounds = 8;
  {
    Result<RenderState> state = RenderState::Open(db, CornellBundle());
    ASSERT_TRUE(state.ok()) << state.error();
    for (uint32_t round = 0; round < kRounds; ++round) {
      ASSERT_TRUE(state->SaveRound(StateAfter(round)).ok());
    }
    ASSERT_TRUE(state->Finish().ok());
    size_t reported = 0;
    for (const RenderState::Report& r : state->TakeReports()) {
      EXPECT_EQ(r.cost.bytes, 2 * 24 * 250000u + 32 + 32) << "round " << r.round;
      ++reported;
    }
    EXPECT_GE(reported, 2u);  // the first and the last at least
  }
  Result<store::JobStore> s = store::JobStore::Open(db);
  ASSERT_TRUE(s.ok()) << s.error();
  Result<std::vector<store::RoundRecord>> rows = s->ListRounds(1);
  ASSERT_TRUE(rows.ok()) << rows.error();
  ASSERT_EQ(rows->size(), kRounds);
  for (uint32_t round = 0; round < kRounds; ++round) {
    EXPECT_EQ((*rows)[round].round, round);
    EXPECT_EQ((*rows)[round].rays, 1000u);
  }
  Result<std::optional<store::Checkpoint>> last = s->LoadLatestCheckpoint(1);
  ASSERT_TRUE(last.ok()) << last.error();
  ASSERT_TRUE(last->has_value());
  const SolveState expected = StateAfter(kRounds - 1);
  EXPECT_EQ((*last)->round, kRounds - 1);
  EXPECT_EQ((*last)->rounds_done, kRounds);
  ASSERT_EQ((*last)->radiosity.size(), expected.radiosity.size());
  EXPECT_EQ(0, std::memcmp((*last)->radiosity.data(), expected.radiosity.data(),
                           expected.radiosity.size() * sizeof(Rgb)));
  EXPECT_EQ(0, std::memcmp((*last)->unshot.data(), expected.unshot.data(),
                           expected.unshot.size() * sizeof(Rgb)));
  EXPECT_EQ((*last)->energy.unshot, expected.energy.unshot);

  // A render opened on it again resumes from that checkpoint.
  Result<RenderState> again = RenderState::Open(db, CornellBundle());
  ASSERT_TRUE(again.ok()) << again.error();
  ASSERT_NE(again->resume(), nullptr);
  EXPECT_EQ(again->resume()->round, kRounds - 1);
  EXPECT_EQ(again->resume()->totals.rays, 1000u * kRounds);
}

}  // namespace
}  // namespace radfarm
