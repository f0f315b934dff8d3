// CheckpointWriter: render --db's store writes on a thread of their own, in order, one checkpoint
// pending at a time, the first failure stopping the rest.
#include "cli/checkpoint_writer.h"

#include <gtest/gtest.h>

#include <future>
#include <string>
#include <vector>

#include "testing/temp_dir.h"

namespace radfarm {
namespace {

class CheckpointWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<store::JobStore> s = store::JobStore::Open(dir_.File("render.db"));
    ASSERT_TRUE(s.ok()) << s.error();
    store_.emplace(std::move(*s));
  }

  testing::TempDir dir_;
  std::optional<store::JobStore> store_;
};

TEST_F(CheckpointWriterTest, RunsWorkInOrderAndDrainWaitsForIt) {
  std::vector<int> order;  // written by the writer's thread only, read after Drain
  CheckpointWriter writer(*store_);
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(writer
                    .Submit(
                        [&order, k](store::JobStore&) -> Status {
                          order.push_back(k);
                          return Ok{};
                        },
                        k % 3 == 0)
                    .ok());
  }
  ASSERT_TRUE(writer.Drain().ok());
  ASSERT_EQ(order.size(), 20u);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(order[k], k);
  EXPECT_FALSE(writer.checkpoint_pending());
}

TEST_F(CheckpointWriterTest, ACheckpointIsPendingUntilItsWorkHasRun) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  CheckpointWriter writer(*store_);
  ASSERT_TRUE(writer
                  .Submit(
                      [released](store::JobStore&) -> Status {
                        released.wait();
                        return Ok{};
                      },
                      true)
                  .ok());
  ASSERT_TRUE(writer.Submit([](store::JobStore&) -> Status { return Ok{}; }, false).ok());
  EXPECT_TRUE(writer.checkpoint_pending());  // queued or running: it waits for `release`
  release.set_value();
  ASSERT_TRUE(writer.Drain().ok());
  EXPECT_FALSE(writer.checkpoint_pending());
}

TEST_F(CheckpointWriterTest, AFailureStopsLaterWorkAndIsReturned) {
  int ran_after = 0;
  CheckpointWriter writer(*store_);
  ASSERT_TRUE(
      writer.Submit([](store::JobStore&) -> Status { return Error{"disk full"}; }, true).ok());
  // Queued behind the failure: never runs.
  (void)writer.Submit(
      [&ran_after](store::JobStore&) -> Status {
        ++ran_after;
        return Ok{};
      },
      false);
  const Status drained = writer.Drain();
  ASSERT_FALSE(drained.ok());
  EXPECT_EQ(drained.error(), "disk full");
  EXPECT_EQ(ran_after, 0);
  const Status refused = writer.Submit([](store::JobStore&) -> Status { return Ok{}; }, false);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error(), "disk full");
  EXPECT_FALSE(writer.checkpoint_pending());
}

TEST_F(CheckpointWriterTest, TheDestructorRunsWhatIsQueued) {
  int ran = 0;
  {
    CheckpointWriter writer(*store_);
    for (int k = 0; k < 5; ++k) {
      ASSERT_TRUE(writer
                      .Submit(
                          [&ran](store::JobStore&) -> Status {
                            ++ran;
                            return Ok{};
                          },
                          true)
                      .ok());
    }
  }
  EXPECT_EQ(ran, 5);
}

}  // namespace
}  // namespace radfarm
