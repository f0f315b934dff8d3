#include "protocol/frame_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "protocol/message_checks.h"
#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol {
namespace {

using testing::SampleMessages;

TEST(ProtocolCodecTest, SamplesCoverEveryMessageTypeAndAreValid) {
  const std::vector<Message> samples = SampleMessages();
  ASSERT_EQ(samples.size(), std::variant_size_v<Message>);
  for (size_t i = 0; i < samples.size(); ++i) {
    EXPECT_EQ(samples[i].index(), i);
    EXPECT_TRUE(CheckMessage(samples[i])) << CheckMessage(samples[i]).error();
  }
}

TEST(ProtocolCodecTest, StartSamplesAreValidAndRoundTrip) {
  for (const Message& message : [] {
         std::vector<Message> all = testing::StartSamples();
         for (Message& m : testing::ScoreSamples()) all.push_back(std::move(m));
         return all;
       }()) {
    EXPECT_TRUE(CheckMessage(message)) << CheckMessage(message).error();
    Result<DecodedFrame> decoded = DecodeFrame(EncodeFrame(message));
    ASSERT_TRUE(decoded) << MessageName(message) << ": " << decoded.error();
    EXPECT_EQ(decoded->message, message);
  }
}

TEST(ProtocolCodecTest, EveryMessageTypeRoundTrips) {
  for (const Message& message : SampleMessages()) {
    const std::vector<uint8_t> frame = EncodeFrame(message);
    Result<DecodedFrame> decoded = DecodeFrame(frame);
    ASSERT_TRUE(decoded) << MessageName(message) << ": " << decoded.error();
    EXPECT_EQ(decoded->version, kProtocolVersion);
    EXPECT_TRUE(decoded->message == message) << MessageName(message);
  }
}

TEST(ProtocolCodecTest, DefaultValuedMessagesRoundTrip) {
  // Zero fields are left out of a FlatBuffer; they must come back as zeros.
  const std::vector<Message> messages = {
      CancelMsg{0},
      HeartbeatMsg{0, 0, 0},
      DrainMsg{DrainMode::kFinishLeases, false},
      CloseMsg{CloseCode::kNormal, ""},
      LeaseResultMsg{{BatchOutcome{{}, {}, 0, 0, 0, 0, 0}}},
  };
  for (const Message& message : messages) {
    Result<DecodedFrame> decoded = DecodeFrame(EncodeFrame(message));
    ASSERT_TRUE(decoded) << MessageName(message) << ": " << decoded.error();
    EXPECT_TRUE(decoded->message == message) << MessageName(message);
  }
}

// FlatBuffers aligns an empty vector of structs only to 4 bytes: a LeaseResult whose batches all
// missed every patch (a tail round's few rays per shooter) must still decode. The master closed
// such an agent as sending a malformed frame (IdleAgentTest, every round on the agents).
TEST(ProtocolCodecTest, ALeaseResultWithoutHitsRoundTrips) {
  for (uint32_t batches = 1; batches <= 4; ++batches) {
    for (uint64_t job : {uint64_t{1}, uint64_t{1} << 40}) {
      LeaseResultMsg message;
      for (uint32_t k = 0; k < batches; ++k) {
        message.results.push_back({{job, 100 + k, k + 1}, {}, 7, 1, 0, 0, 0.5});
      }
      Result<DecodedFrame> decoded = DecodeFrame(EncodeFrame(message));
      ASSERT_TRUE(decoded) << batches << " batches: " << decoded.error();
      EXPECT_TRUE(decoded->message == Message{message});
    }
  }
}

// Version 5 packs a LeaseResult's hits; a version-4 frame still carries them as structs, so a
// version-4 agent works with this master. A short batch of a big scene's patches (ids a few
// dozen apart, weight 1) takes 2 bytes a hit instead of 16: with the batches' counts (64 bytes a
// batch either way), a sixth of the frame.
TEST(ProtocolCodecTest, ALeaseResultRoundTripsInBothFormsAndPackedIsASixth) {
  LeaseResultMsg message;
  for (uint32_t b = 0; b < 8; ++b) {
    BatchOutcome r{{7, 100 + b, 1}, {}, 3, 3, 0, 0, 0.01};
    for (uint32_t k = 0; k < 150; ++k) r.hits.push_back({k * 37 + b, k % 7 == 0 ? 2u : 1u});
    message.results.push_back(r);
  }
  const std::vector<uint8_t> packed = EncodeFrame(message, 5), structs = EncodeFrame(message, 4);
  for (const std::vector<uint8_t>* frame : {&packed, &structs}) {
    Result<DecodedFrame> decoded = DecodeFrame(*frame);
    ASSERT_TRUE(decoded) << decoded.error();
    EXPECT_TRUE(decoded->message == Message{message});
  }
  EXPECT_GT(structs.size(), 8 * 150 * 16u);
  EXPECT_LT(packed.size(), structs.size() / 6);
}

TEST(ProtocolCodecTest, FrameStartsWithLittleEndianLengthAndIdentifier) {
  const std::vector<uint8_t> frame = EncodeFrame(CancelMsg{1});
  ASSERT_GE(frame.size(), 12u);
  EXPECT_EQ(ReadLengthPrefix(frame.data()), frame.size() - kLengthPrefixBytes);
  EXPECT_EQ(std::string(frame.begin() + 8, frame.begin() + 12), "RDFM");
}

TEST(ProtocolCodecTest, VersionIsCarried) {
  Result<DecodedFrame> decoded = DecodeFrame(EncodeFrame(CancelMsg{1}, 7));
  ASSERT_TRUE(decoded) << decoded.error();
  EXPECT_EQ(decoded->version, 7);
  Result<DecodedFrame> zero = DecodeFrame(EncodeFrame(CancelMsg{1}, 0));
  ASSERT_FALSE(zero);
  EXPECT_NE(zero.error().find("version 0"), std::string::npos) << zero.error();
}

TEST(ProtocolCodecTest, MisalignedBufferDecodes) {
  const std::vector<uint8_t> frame = EncodeFrame(testing::SampleOf<LeaseResultMsg>());
  std::vector<uint8_t> shifted(frame.size() + 1);
  std::copy(frame.begin(), frame.end(), shifted.begin() + 1);
  Result<DecodedFrame> decoded = DecodeFrame(std::span(shifted).subspan(1));
  ASSERT_TRUE(decoded) << decoded.error();
  EXPECT_TRUE(decoded->message == Message{testing::SampleOf<LeaseResultMsg>()});
}

TEST(ProtocolCodecTest, LargestSceneChunkFitsTheSmallestPeerLimit) {
  SceneChunkMsg chunk{testing::Pattern(1), uint64_t{1} << 40, 0,
                      std::vector<uint8_t>(kMaxSceneChunkBytes, 0xab), uint64_t{1} << 42};
  const std::vector<uint8_t> frame = EncodeFrame(chunk);
  EXPECT_LE(frame.size() - kLengthPrefixBytes, kMinPeerFrameBytes);
  Result<DecodedFrame> decoded = DecodeFrame(frame, kMinPeerFrameBytes);
  ASSERT_TRUE(decoded) << decoded.error();
  EXPECT_TRUE(decoded->message == Message{chunk});
}

}  // namespace
}  // namespace radfarm::protocol
