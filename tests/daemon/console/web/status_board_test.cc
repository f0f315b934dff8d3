#include "daemon/console/web/status_board.h"

#include <gtest/gtest.h>

#include <thread>

namespace radfarm::web {
namespace {

using Clock = std::chrono::steady_clock;

StatusSnapshot Snapshot(const std::string& json) {
  StatusSnapshot s;
  s.status_json = json;
  return s;
}

TEST(StatusBoardTest, PublishNumbersSnapshotsAndKeepsTheOldOnesIntactForTheirReaders) {
  StatusBoard board;
  EXPECT_EQ(board.Latest(), nullptr);
  board.Publish(Snapshot("one"));
  const auto first = board.Latest();
  board.Publish(Snapshot("two"));
  EXPECT_EQ(first->version, 1u);
  EXPECT_EQ(first->status_json, "one");  // a reader's snapshot never changes under it
  EXPECT_EQ(board.Latest()->version, 2u);
  EXPECT_EQ(board.Latest()->status_json, "two");
}

TEST(StatusBoardTest, WaitNewerReturnsAtOnceWhenAlreadyNewerAndWakesOnPublish) {
  StatusBoard board;
  board.Publish(Snapshot("one"));
  EXPECT_EQ(board.WaitNewer(0, Clock::now())->version, 1u);
  std::thread publisher([&] { board.Publish(Snapshot("two")); });
  const auto next = board.WaitNewer(1, Clock::now() + std::chrono::seconds(60));
  publisher.join();
  ASSERT_NE(next, nullptr);
  EXPECT_EQ(next->version, 2u);
}

TEST(StatusBoardTest, WaitNewerGivesTheSameSnapshotAtTheDeadline) {
  StatusBoard board;
  board.Publish(Snapshot("one"));
  EXPECT_EQ(board.WaitNewer(1, Clock::now())->version, 1u);
}

TEST(StatusBoardTest, CloseWakesWaitersWithNull) {
  StatusBoard board;
  board.Publish(Snapshot("one"));
  std::thread closer([&] { board.Close(); });
  EXPECT_EQ(board.WaitNewer(1, Clock::now() + std::chrono::seconds(60)), nullptr);
  closer.join();
  EXPECT_TRUE(board.closed());
}

}  // namespace
}  // namespace radfarm::web
