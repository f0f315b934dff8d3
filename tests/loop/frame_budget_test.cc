// FrameBudget with the splitters that charge it: connections trickling big frames hold at most the
// budget between them. Before it, 60 connections each 15 MiB into a frame held 938 MB in radfarmd.
#include "loop/frame_budget.h"

#include <gtest/gtest.h>

#include <memory>
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
  int refused = 0;
  const std::vector<uint8_t> partial = PartialFrame(15u << 20, 4u << 20);
  for (int i = 0; i < 60; ++i) {
    connections.push_back(std::make_unique<FrameSplitter>(kFrameLimit, budget));
    const Status s = FeedInChunks(*connections.back(), partial);
    if (!s) {
      ++refused;
      EXPECT_NE(s.error().find("unfinished frames already hold"), std::string::npos) << s.error();
      EXPECT_NE(s.error().find("--max-frame-bytes-held"), std::string::npos) << s.error();
      EXPECT_TRUE(connections.back()->failed());
    }
    size_t capacity = 0;
    for (const auto& c : connections) capacity += c->buffer_capacity();
    EXPECT_LE(capacity, budget->limit()) << "after connection " << i;
    EXPECT_LE(budget->held(), budget->limit());
  }
  // A buffer holds its data, doubling as it grows: at most 8 of 4 MiB fit in 32 MiB.
  EXPECT_GE(refused, 60 - 8);
  EXPECT_EQ(budget->refused(), uint64_t(refused));
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

TEST(FrameBudgetTest, AFrameThatWouldPassTheBudgetFailsItsStreamOnly) {
  auto budget = std::make_shared<FrameBudget>(1u << 20, "the budget");
  FrameSplitter hog(kFrameLimit, budget), other(kFrameLimit, budget);
  ASSERT_TRUE(FeedInChunks(hog, PartialFrame(4u << 20, 768u << 10)).ok());
  EXPECT_FALSE(FeedInChunks(other, PartialFrame(4u << 20, 512u << 10)).ok());
  EXPECT_TRUE(other.failed());
  EXPECT_FALSE(hog.failed());
  // The refused one took nothing; the hog still holds its share.
  EXPECT_EQ(budget->held(), hog.buffer_capacity());
  const std::vector<uint8_t> small = Frame(Bytes("a small frame"));
  FrameSplitter third(kFrameLimit, budget);
  int frames = 0;
  ASSERT_TRUE(third.Feed(small, [&](auto) { return ++frames, true; }).ok());
  EXPECT_EQ(frames, 1);  // a whole frame in one chunk is never buffered, so never refused
}

}  // namespace
}  // namespace radfarm::loop
