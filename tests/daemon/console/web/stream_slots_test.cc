#include "daemon/console/web/stream_slots.h"

#include <gtest/gtest.h>

#include <vector>

namespace radfarm::web {
namespace {

// 64 open tabs each held a stream and a connection for good; the cap makes the newest evict the
// oldest.
TEST(StreamSlotsTest, OneOverTheCapEvictsTheOldest) {
  StatusBoard board;
  StreamSlots slots(board, 3, 3);
  std::vector<std::unique_ptr<StreamSlots::Ticket>> tickets;
  tickets.push_back(slots.Join("10.0.0.1"));
  tickets.push_back(slots.Join("10.0.0.2"));
  tickets.push_back(slots.Join("10.0.0.3"));
  EXPECT_EQ(slots.size(), 3u);
  tickets.push_back(slots.Join("10.0.0.4"));
  EXPECT_TRUE(tickets[0]->evicted());
  EXPECT_FALSE(tickets[1]->evicted());
  EXPECT_FALSE(tickets[3]->evicted());
  EXPECT_EQ(slots.size(), 3u);
}

TEST(StreamSlotsTest, OneAddressOverItsCapEvictsItsOwnOldestNotOthers) {
  StatusBoard board;
  StreamSlots slots(board, 10, 2);
  auto other = slots.Join("10.0.0.9");
  auto first = slots.Join("10.0.0.1");
  auto second = slots.Join("10.0.0.1");
  auto third = slots.Join("10.0.0.1");
  EXPECT_FALSE(other->evicted());
  EXPECT_TRUE(first->evicted());
  EXPECT_FALSE(second->evicted());
  EXPECT_FALSE(third->evicted());
  EXPECT_EQ(slots.size(), 3u);
}

TEST(StreamSlotsTest, AStreamThatEndsFreesItsSlot) {
  StatusBoard board;
  StreamSlots slots(board, 2, 2);
  auto first = slots.Join("10.0.0.1");
  slots.Join("10.0.0.1").reset();
  auto third = slots.Join("10.0.0.1");
  EXPECT_FALSE(first->evicted());
  EXPECT_EQ(slots.size(), 2u);
}

}  // namespace
}  // namespace radfarm::web
