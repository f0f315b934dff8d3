#include "agent/lease_book.h"

#include <gtest/gtest.h>

namespace radfarm::agent {
namespace {

protocol::AssignedBatch Lease(uint64_t job, uint64_t batch, uint8_t scene = 1) {
  protocol::AssignedBatch a;
  a.lease = {job, batch, 0};
  a.scene_hash.fill(scene);
  return a;
}

std::shared_ptr<const PreparedScene> Scene() { return std::make_shared<PreparedScene>(); }

TEST(LeaseBookTest, QueuedLeasesRunInArrivalOrder) {
  LeaseBook book;
  HeldLease& a = book.Add(Lease(1, 1));
  HeldLease& b = book.Add(Lease(1, 2));
  EXPECT_EQ(book.PopQueued(), nullptr);  // both still wait for their scene
  book.MarkQueued(b, Scene());
  book.MarkQueued(a, Scene());
  HeldLease* first = book.PopQueued();
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->assignment.lease.batch_id, 2u);
  EXPECT_EQ(first->stage, LeaseStage::kRunning);
  EXPECT_EQ(book.PopQueued()->assignment.lease.batch_id, 1u);
  EXPECT_EQ(book.PopQueued(), nullptr);
  EXPECT_EQ(book.CountInStage(LeaseStage::kRunning), 2u);
}

TEST(LeaseBookTest, CancelRemovesQueuedAndRunningLeasesOfTheJobOnly) {
  LeaseBook book;
  for (uint64_t batch = 1; batch <= 3; ++batch) book.MarkQueued(book.Add(Lease(7, batch)), Scene());
  book.MarkQueued(book.Add(Lease(8, 1)), Scene());
  const uint64_t running = book.PopQueued()->id;  // job 7 batch 1
  const std::vector<protocol::LeaseRef> dropped = book.RemoveJob(7);
  EXPECT_EQ(dropped.size(), 3u);
  EXPECT_EQ(book.Find(running), nullptr);  // its result will find nothing
  HeldLease* next = book.PopQueued();
  ASSERT_NE(next, nullptr);
  EXPECT_EQ(next->assignment.lease.job_id, 8u);
  EXPECT_EQ(book.PopQueued(), nullptr);
}

TEST(LeaseBookTest, IdsAreNeverReused) {
  LeaseBook book;
  const uint64_t first = book.Add(Lease(1, 1)).id;
  book.RemoveAll();
  EXPECT_GT(book.Add(Lease(1, 1)).id, first);
}

TEST(LeaseBookTest, FindsLeasesByReferenceAndBySceneAwaited) {
  LeaseBook book;
  book.Add(Lease(1, 1, /*scene=*/5));
  HeldLease& other = book.Add(Lease(1, 2, /*scene=*/6));
  book.Add(Lease(2, 1, /*scene=*/5));
  EXPECT_TRUE(book.Holds({1, 2, 0}));
  EXPECT_FALSE(book.Holds({1, 2, 1}));
  protocol::SceneHash five;
  five.fill(5);
  EXPECT_EQ(book.AwaitingScene(five).size(), 2u);
  book.MarkQueued(other, Scene());
  protocol::SceneHash six;
  six.fill(6);
  EXPECT_TRUE(book.AwaitingScene(six).empty());
  EXPECT_EQ(book.RemoveAll().size(), 3u);
  EXPECT_TRUE(book.empty());
}

}  // namespace
}  // namespace radfarm::agent
