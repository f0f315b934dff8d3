#include "protocol/frame_decoder.h"

#include <gtest/gtest.h>

#include <random>

#include "protocol/frame_codec.h"
#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol {
namespace {

using testing::SampleMessages;

// Every sample message, back to back, as one byte stream.
std::vector<uint8_t> SampleStream() {
  std::vector<uint8_t> stream;
  for (const Message& m : SampleMessages()) {
    const std::vector<uint8_t> frame = EncodeFrame(m);
    stream.insert(stream.end(), frame.begin(), frame.end());
  }
  return stream;
}

// Feeds `stream` in chunks of the sizes `next_chunk` returns and collects the messages.
template <typename ChunkSize>
std::vector<Message> DecodeInChunks(const std::vector<uint8_t>& stream, ChunkSize next_chunk,
                                    FrameDecoder* decoder) {
  std::vector<Message> out;
  size_t pos = 0;
  while (pos < stream.size()) {
    const size_t n = std::min<size_t>(next_chunk(), stream.size() - pos);
    EXPECT_TRUE(decoder->Feed(std::span(stream).subspan(pos, n)));
    pos += n;
    for (;;) {
      Result<std::optional<DecodedFrame>> next = decoder->Next();
      EXPECT_TRUE(next) << next.error();
      if (!next || !*next) break;
      out.push_back(std::move((*next)->message));
    }
  }
  return out;
}

TEST(ProtocolDecoderTest, OneByteChunks) {
  FrameDecoder decoder;
  const std::vector<Message> out = DecodeInChunks(
      SampleStream(), [] { return 1; }, &decoder);
  EXPECT_TRUE(out == SampleMessages());
  EXPECT_EQ(decoder.buffered_bytes(), 0u);
}

TEST(ProtocolDecoderTest, WholeStreamInOneChunk) {
  FrameDecoder decoder;
  const std::vector<uint8_t> stream = SampleStream();
  const std::vector<Message> out = DecodeInChunks(
      stream, [&] { return stream.size(); }, &decoder);
  EXPECT_TRUE(out == SampleMessages());
}

TEST(ProtocolDecoderTest, RandomChunkBoundaries) {
  std::mt19937 rng(4);
  const std::vector<uint8_t> stream = SampleStream();
  for (int trial = 0; trial < 200; ++trial) {
    FrameDecoder decoder;
    const size_t max_chunk = 1 + rng() % 100;
    const std::vector<Message> out = DecodeInChunks(
        stream, [&] { return 1 + rng() % max_chunk; }, &decoder);
    ASSERT_TRUE(out == SampleMessages()) << "trial " << trial;
    EXPECT_EQ(decoder.buffered_bytes(), 0u);
  }
}

TEST(ProtocolDecoderTest, EverySplitPointOfTwoFrames) {
  const std::vector<uint8_t> a = EncodeFrame(testing::SampleOf<LeaseResultMsg>());
  const std::vector<uint8_t> b = EncodeFrame(testing::SampleOf<LeaseAssignmentMsg>());
  std::vector<uint8_t> stream = a;
  stream.insert(stream.end(), b.begin(), b.end());
  for (size_t split = 0; split <= stream.size(); ++split) {
    FrameDecoder decoder;
    size_t call = 0;
    const std::vector<Message> out = DecodeInChunks(
        stream, [&] { return call++ == 0 ? std::max<size_t>(split, 1) : stream.size(); }, &decoder);
    ASSERT_EQ(out.size(), 2u) << split;
    EXPECT_TRUE(out[0] == Message{testing::SampleOf<LeaseResultMsg>()});
    EXPECT_TRUE(out[1] == Message{testing::SampleOf<LeaseAssignmentMsg>()});
  }
}

TEST(ProtocolDecoderTest, ErrorIsStickyAndDropsTheBuffer) {
  FrameDecoder decoder;
  std::vector<uint8_t> frame = EncodeFrame(CancelMsg{9});
  frame[kLengthPrefixBytes + 5] ^= 0xff;  // identifier
  ASSERT_TRUE(decoder.Feed(frame));
  Result<std::optional<DecodedFrame>> first = decoder.Next();
  ASSERT_FALSE(first);
  EXPECT_TRUE(decoder.failed());
  EXPECT_EQ(decoder.buffered_bytes(), 0u);
  // A good frame afterwards does not revive the stream.
  EXPECT_FALSE(decoder.Feed(EncodeFrame(CancelMsg{9})));
  Result<std::optional<DecodedFrame>> again = decoder.Next();
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error(), first.error());
}

TEST(ProtocolDecoderTest, GoodFramesBeforeABadOneAreDelivered) {
  std::vector<uint8_t> stream = EncodeFrame(CancelMsg{1});
  const std::vector<uint8_t> bad = {0xff, 0xff, 0xff, 0x7f};
  stream.insert(stream.end(), bad.begin(), bad.end());
  FrameDecoder decoder;
  ASSERT_TRUE(decoder.Feed(stream));
  Result<std::optional<DecodedFrame>> first = decoder.Next();
  ASSERT_TRUE(first && *first);
  EXPECT_TRUE((*first)->message == Message{CancelMsg{1}});
  EXPECT_FALSE(decoder.Next());
}

TEST(ProtocolDecoderTest, ConfigurableLimit) {
  const std::vector<uint8_t> chunk = EncodeFrame(testing::SampleOf<SceneChunkMsg>());
  FrameDecoder small(static_cast<uint32_t>(chunk.size() - kLengthPrefixBytes - 1));
  ASSERT_TRUE(small.Feed(std::span(chunk).first(kLengthPrefixBytes)));
  EXPECT_FALSE(small.Next());  // judged on the prefix alone
  FrameDecoder exact(static_cast<uint32_t>(chunk.size() - kLengthPrefixBytes));
  ASSERT_TRUE(exact.Feed(chunk));
  Result<std::optional<DecodedFrame>> next = exact.Next();
  ASSERT_TRUE(next && *next);
}

TEST(ProtocolDecoderTest, BufferStaysAboutOneFrameWhenDrained) {
  FrameDecoder decoder;
  const std::vector<uint8_t> frame = EncodeFrame(testing::SampleOf<LeaseResultMsg>());
  for (int i = 0; i < 1000; ++i) {
    ASSERT_TRUE(decoder.Feed(std::span(frame).first(frame.size() / 2)));
    ASSERT_TRUE(decoder.Next());
    ASSERT_TRUE(decoder.Feed(std::span(frame).subspan(frame.size() / 2)));
    Result<std::optional<DecodedFrame>> next = decoder.Next();
    ASSERT_TRUE(next && *next);
    ASSERT_EQ(decoder.buffered_bytes(), 0u);
  }
}

}  // namespace
}  // namespace radfarm::protocol
