// FrameBudget with the splitters that charge it: connections trickling big frames hold at most the
// budget between them (60 connections each 15 MiB into a frame held 938 MB in radfarmd without
// it), and a frame that would pass it closes the connection holding the most.
#include "loop/frame_budget.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "loop/frame_splitter.h"
#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::Bytes;
using testing::Frame;

constexpr uint32_t kFrameLimit = 16u << 20;

// The prefix of a frame of `announced` bytes and the first `sent` bytes of its payload.
std::vector<uint8_t> PartialFrame(uint32_t announced, size_t sent) {
  std::vector<uint8_t> bytes(4 + sent, 't');
  WriteFramePrefix(announced, bytes.data());
  return bytes;
}

Status FeedInChunks(FrameSplitter& splitter, const std::vector<uint8_t>& bytes) {
  constexpr size_t kChunk = 64 * 1024;  // as libuv reads
  for (size_t at = 0; at < bytes.size(); at += kChunk) {
    const size_t n = std::min(kChunk, bytes.size() - at);
    Status s = splitter.Feed(std::span(bytes).subspan(at, n), [](auto) { return true; });
    if (!s) return s;
  }
  return Ok{};
}

TEST(FrameBudgetTest, SixtyTricklingConnectionsHoldAtMostTheBudgetBetweenThem) {
  auto budget = std::make_shared<FrameBudget>(32u << 20, "--max-frame-bytes-held");
  std::vector<std::unique_ptr<FrameSplitter>> connections;
  std::vector<std::string> reasons;  // of connections refused or evicted
  const std::vector<uint8_t> partial = PartialFrame(15u << 20, 4u << 20);
  for (int i = 0; i < 60; ++i) {
    connections.push_back(std::make_unique<FrameSplitter>(kFrameLimit, budget));
    connections.back()->set_on_evicted([&](const std::string& why) { reasons.push_back(why); });
    const Status s = FeedInChunks(*connections.back(), partial);
    if (!s) reasons.push_back(s.error());
    size_t capacity = 0;
    for (const auto& c : connections) capacity += c->buffer_capacity();
    EXPECT_LE(capacity, budget->limit()) << "after connection " << i;
    EXPECT_LE(budget->held(), budget->limit());
  }
  // A buffer holds its data, doubling as it grows: at most 8 of 4 MiB fit in 32 MiB.
  size_t failed = 0;
  for (const auto& c : connections) failed += c->failed() ? 1 : 0;
  EXPECT_GE(failed, 60u - 8);
  EXPECT_EQ(budget->refused(), failed);
  EXPECT_EQ(reasons.size(), failed);
  for (const std::string& why : reasons) {
    EXPECT_NE(why.find("unfinished frames already hold"), std::string::npos) << why;
    EXPECT_NE(why.find("--max-frame-bytes-held"), std::string::npos) << why;
  }
  connections.clear();
  EXPECT_EQ(budget->held(), 0u);  // a connection that goes gives its share back
}

TEST(FrameBudgetTest, AFinishedFrameGivesItsShareBack) {
  auto budget = std::make_shared<FrameBudget>(8u << 20, "the budget");
  FrameSplitter splitter(kFrameLimit, budget);
  const std::vector<uint8_t> big = Frame(std::vector<uint8_t>(6u << 20, 'b'));
  ASSERT_TRUE(FeedInChunks(splitter, big).ok());
  EXPECT_EQ(budget->held(), 0u);
  EXPECT_GE(budget->peak(), 6u << 20);
  EXPECT_LE(budget->peak(), 8u << 20);  // the buffer grew to the frame's length, no further
  // Twice more: the budget was given back each time, so neither is refused.
  ASSERT_TRUE(FeedInChunks(splitter, big).ok());
  ASSERT_TRUE(FeedInChunks(splitter, big).ok());
  EXPECT_EQ(budget->refused(), 0u);
}

// Hostile neighbours: one agent 768 KiB into a huge frame held the whole budget, and every honest
// agent's next partial frame was refused. Now the frame that would pass the budget closes the
// connection holding the most instead.
TEST(FrameBudgetTest, AFrameThatWouldPassTheBudgetEvictsTheLargestHolderNotTheSmallFrame) {
  auto budget = std::make_shared<FrameBudget>(1u << 20, "the budget");
  FrameSplitter hog(kFrameLimit, budget), honest(kFrameLimit, budget);
  std::vector<std::string> evicted;
  hog.set_on_evicted([&](const std::string& why) { evicted.push_back(why); });
  honest.set_on_evicted([&](const std::string& why) { evicted.push_back("honest: " + why); });
  ASSERT_TRUE(FeedInChunks(hog, PartialFrame(4u << 20, 768u << 10)).ok());
  EXPECT_EQ(budget->held(), hog.buffer_capacity());

  ASSERT_TRUE(FeedInChunks(honest, PartialFrame(512u << 10, 256u << 10)).ok());
  EXPECT_FALSE(honest.failed());
  EXPECT_TRUE(hog.failed());
  ASSERT_EQ(evicted.size(), 1u);
  EXPECT_NE(evicted[0].find("closed holding the most bytes of unfinished frames"),
            std::string::npos)
      << evicted[0];
  EXPECT_NE(evicted[0].find("(the budget)"), std::string::npos) << evicted[0];
  // The hog's buffer went at once; the budget holds the honest frame only.
  EXPECT_EQ(hog.buffer_capacity(), 0u);
  EXPECT_EQ(budget->held(), honest.buffer_capacity());
  EXPECT_EQ(budget->evicted(), 1u);
  EXPECT_EQ(budget->refused(), 1u);
  EXPECT_FALSE(FeedInChunks(hog, PartialFrame(4u << 20, 1)).ok());  // a stream cannot resume

  // The honest frame completes and gives its share back.
  int frames = 0;
  const std::vector<uint8_t> rest(256u << 10, 't');
  ASSERT_TRUE(honest.Feed(rest, [&](auto) { return ++frames, true; }).ok());
  EXPECT_EQ(frames, 1);
  EXPECT_EQ(budget->held(), 0u);
}

TEST(FrameBudgetTest, TheLargestHolderAskingForMoreIsRefusedAndTheOthersKept) {
  auto budget = std::make_shared<FrameBudget>(1u << 20, "the budget");
  FrameSplitter small(kFrameLimit, budget), hog(kFrameLimit, budget);
  bool small_evicted = false;
  small.set_on_evicted([&](const std::string&) { small_evicted = true; });
  ASSERT_TRUE(FeedInChunks(small, PartialFrame(4u << 20, 128u << 10)).ok());
  const Status s = FeedInChunks(hog, PartialFrame(4u << 20, 1u << 20));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("unfinished frames already hold"), std::string::npos) << s.error();
  EXPECT_TRUE(hog.failed());
  EXPECT_FALSE(small.failed());
  EXPECT_FALSE(small_evicted);
  EXPECT_EQ(budget->evicted(), 0u);
  EXPECT_EQ(budget->refused(), 1u);
  // The refused one took nothing more than it held before; the small one keeps its share.
  EXPECT_EQ(budget->held(), small.buffer_capacity() + hog.buffer_capacity());
  const std::vector<uint8_t> whole = Frame(Bytes("a small frame"));
  FrameSplitter third(kFrameLimit, budget);
  int frames = 0;
  ASSERT_TRUE(third.Feed(whole, [&](auto) { return ++frames, true; }).ok());
  EXPECT_EQ(frames, 1);  // a whole frame in one chunk is never buffered, so never refused
}

}  // namespace
}  // namespace radfarm::loop
