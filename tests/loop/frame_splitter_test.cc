#include "loop/frame_splitter.h"

#include <gtest/gtest.h>

#include "loop_test_util.h"

namespace radfarm::loop {
namespace {

using testing::Bytes;
using testing::Frame;

std::vector<std::string> FeedAll(FrameSplitter& splitter, const std::vector<uint8_t>& bytes,
                                 size_t chunk) {
  std::vector<std::string> frames;
  for (size_t at = 0; at < bytes.size(); at += chunk) {
    const size_t n = std::min(chunk, bytes.size() - at);
    const Status status =
        splitter.Feed(std::span(bytes).subspan(at, n), [&](std::span<const uint8_t> payload) {
          frames.emplace_back(payload.begin(), payload.end());
          return true;
        });
    EXPECT_TRUE(status.ok()) << status.error();
  }
  return frames;
}

TEST(FrameSplitterTest, PrefixIsLittleEndian) {
  uint8_t prefix[4];
  WriteFramePrefix(0x01020304, prefix);
  EXPECT_EQ(prefix[0], 0x04);
  EXPECT_EQ(prefix[3], 0x01);
  EXPECT_EQ(ReadFramePrefix(prefix), 0x01020304u);
}

TEST(FrameSplitterTest, SplitsAStreamCutAtEveryChunkSize) {
  std::vector<uint8_t> stream;
  const std::vector<std::string> sent = {"hello", "", "a", std::string(300, 'x'), "last"};
  for (const std::string& text : sent) {
    const std::vector<uint8_t> frame = Frame(Bytes(text));
    stream.insert(stream.end(), frame.begin(), frame.end());
  }
  for (size_t chunk = 1; chunk <= stream.size(); ++chunk) {
    FrameSplitter splitter(1024);
    EXPECT_EQ(FeedAll(splitter, stream, chunk), sent) << "chunk size " << chunk;
    EXPECT_EQ(splitter.buffered_bytes(), 0u);
  }
}

TEST(FrameSplitterTest, OversizedPrefixFailsBeforeThePayloadArrives) {
  FrameSplitter splitter(100);
  std::vector<uint8_t> prefix(4);
  WriteFramePrefix(101, prefix.data());
  bool called = false;
  const Status status = splitter.Feed(prefix, [&](auto) { return called = true; });
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error(), "frame of 101 bytes exceeds the limit of 100 bytes");
  EXPECT_FALSE(called);
  EXPECT_EQ(splitter.buffer_capacity(), 0u);
  EXPECT_TRUE(splitter.failed());
  EXPECT_FALSE(splitter.Feed(Frame(Bytes("ok")), [](auto) { return true; }).ok());  // stays failed
}

// A peer announcing a big (allowed) frame and sending a few bytes costs us those bytes only.
TEST(FrameSplitterTest, BufferGrowsWithArrivedBytesNotTheAnnouncedLength) {
  FrameSplitter splitter(16u << 20);
  std::vector<uint8_t> start(4 + 10, 7);
  WriteFramePrefix(16u << 20, start.data());
  ASSERT_TRUE(splitter.Feed(start, [](auto) { return true; }).ok());
  EXPECT_EQ(splitter.buffered_bytes(), 10u);
  EXPECT_LT(splitter.buffer_capacity(), 4096u);
}

TEST(FrameSplitterTest, PrefixAtTheLimitIsAccepted) {
  FrameSplitter splitter(8);
  const std::vector<uint8_t> frame = Frame(Bytes("12345678"));
  EXPECT_EQ(FeedAll(splitter, frame, 3), std::vector<std::string>{"12345678"});
}

TEST(FrameSplitterTest, StoppingDropsTheRestOfTheChunk) {
  FrameSplitter splitter(100);
  std::vector<uint8_t> stream = Frame(Bytes("one"));
  const std::vector<uint8_t> second = Frame(Bytes("two"));
  stream.insert(stream.end(), second.begin(), second.end());
  int calls = 0;
  ASSERT_TRUE(splitter
                  .Feed(stream,
                        [&](auto) {
                          ++calls;
                          return false;
                        })
                  .ok());
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace radfarm::loop
