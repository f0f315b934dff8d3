// Frames that are cut short, corrupted, oversized or made by hand: every one is rejected with a
// reason (or, for a bit flip inside a value, decodes to another valid message), never a crash.
// The ASan/UBSan build (-DRADFARM_SANITIZE=ON) runs these too.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "frame_generated.h"
#include "protocol/frame_codec.h"
#include "protocol/frame_decoder.h"
#include "protocol/message_checks.h"
#include "tests/protocol/sample_messages.h"

namespace radfarm::protocol {
namespace {

using testing::SampleMessages;

std::vector<uint8_t> WithPrefix(const uint8_t* body, size_t size) {
  std::vector<uint8_t> frame(kLengthPrefixBytes + size);
  for (size_t i = 0; i < kLengthPrefixBytes; ++i) frame[i] = static_cast<uint8_t>(size >> (8 * i));
  std::copy(body, body + size, frame.begin() + kLengthPrefixBytes);
  return frame;
}

bool ErrorMentions(const Result<DecodedFrame>& r, const std::string& text) {
  return !r && r.error().find(text) != std::string::npos;
}

TEST(ProtocolMalformedTest, EveryTruncationIsRejected) {
  for (const Message& message : SampleMessages()) {
    const std::vector<uint8_t> frame = EncodeFrame(message);
    for (size_t n = 0; n < frame.size(); ++n) {
      EXPECT_FALSE(DecodeFrame(std::span(frame).first(n))) << MessageName(message) << " " << n;
      // A stream that stops early is not an error yet: the decoder waits for more.
      FrameDecoder decoder;
      ASSERT_TRUE(decoder.Feed(std::span(frame).first(n)));
      Result<std::optional<DecodedFrame>> next = decoder.Next();
      ASSERT_TRUE(next) << next.error();
      EXPECT_FALSE(*next);
    }
  }
}

TEST(ProtocolMalformedTest, TruncatedBodyWithFixedUpPrefixIsRejected) {
  for (const Message& message : SampleMessages()) {
    const std::vector<uint8_t> frame = EncodeFrame(message);
    const uint8_t* body = frame.data() + kLengthPrefixBytes;
    const size_t size = frame.size() - kLengthPrefixBytes;
    size_t rejected = 0;
    for (size_t n = 0; n < size; ++n) {
      Result<DecodedFrame> r = DecodeFrame(WithPrefix(body, n));
      // Cutting only a string's trailing padding leaves a whole, identical message.
      if (r) {
        EXPECT_TRUE(r->message == message) << MessageName(message) << " cut to " << n;
        EXPECT_GE(n + 4, size) << MessageName(message) << " cut to " << n;
      } else {
        ++rejected;
      }
    }
    EXPECT_GE(rejected + 3, size) << MessageName(message);
  }
}

TEST(ProtocolMalformedTest, EveryBitFlipIsRejectedOrStillValid) {
  size_t flips = 0, rejected = 0;
  for (const Message& message : SampleMessages()) {
    std::vector<uint8_t> frame = EncodeFrame(message);
    for (size_t bit = 0; bit < frame.size() * 8; ++bit) {
      frame[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
      Result<DecodedFrame> r = DecodeFrame(frame);
      ++flips;
      if (!r) {
        ++rejected;
        EXPECT_FALSE(r.error().empty());
      } else {
        // A flip inside a value gives another message, which must still pass every check.
        EXPECT_TRUE(CheckMessage(r->message)) << MessageName(message) << " bit " << bit;
      }
      frame[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    }
  }
  // Flips in the prefix, identifier, offsets and tables are caught; the rest are values.
  EXPECT_GT(rejected, flips / 4) << rejected << " of " << flips;
}

TEST(ProtocolMalformedTest, OversizedLengthPrefixIsRejectedBeforeTheBody) {
  for (uint32_t length : {kDefaultMaxFrameBytes + 1, 0xffffffffu, 0x80000000u}) {
    const uint8_t prefix[4] = {static_cast<uint8_t>(length), static_cast<uint8_t>(length >> 8),
                               static_cast<uint8_t>(length >> 16),
                               static_cast<uint8_t>(length >> 24)};
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.Feed(prefix));
    Result<std::optional<DecodedFrame>> next = decoder.Next();
    ASSERT_FALSE(next);
    EXPECT_NE(next.error().find("exceeds the limit"), std::string::npos) << next.error();
    EXPECT_EQ(decoder.buffered_bytes(), 0u);
    EXPECT_TRUE(decoder.failed());
  }
}

TEST(ProtocolMalformedTest, TooShortLengthPrefixIsRejected) {
  for (uint32_t length : {0u, 1u, kMinFrameBytes - 1}) {
    const uint8_t prefix[4] = {static_cast<uint8_t>(length), 0, 0, 0};
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.Feed(prefix));
    EXPECT_FALSE(decoder.Next());
  }
}

TEST(ProtocolMalformedTest, RandomBytesAreRejected) {
  std::mt19937_64 rng(12345);
  for (int trial = 0; trial < 20000; ++trial) {
    const size_t size = rng() % 200;
    std::vector<uint8_t> bytes(size);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    // With a consistent prefix so the body itself is what gets judged.
    EXPECT_FALSE(DecodeFrame(WithPrefix(bytes.data(), bytes.size())));
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.Feed(bytes));
    for (int i = 0; i < 4; ++i) {
      Result<std::optional<DecodedFrame>> next = decoder.Next();
      if (!next || !*next) break;
    }
  }
}

TEST(ProtocolMalformedTest, RandomBytesBehindAValidHeaderAreRejected) {
  // Keep the identifier so the verifier, not the identifier check, has to catch them.
  std::mt19937_64 rng(777);
  const std::vector<uint8_t> valid = EncodeFrame(testing::SampleOf<LeaseAssignmentMsg>());
  size_t accepted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> frame = valid;
    for (size_t i = kLengthPrefixBytes + 8; i < frame.size(); ++i) {
      if (rng() % 4 == 0) frame[i] = static_cast<uint8_t>(rng());
    }
    Result<DecodedFrame> r = DecodeFrame(frame);
    if (r) {
      ++accepted;
      EXPECT_TRUE(CheckMessage(r->message));
    }
  }
  EXPECT_LT(accepted, 20000u);
}

TEST(ProtocolMalformedTest, WrongIdentifierIsRejected) {
  std::vector<uint8_t> frame = EncodeFrame(CancelMsg{1});
  frame[kLengthPrefixBytes + 4] = 'X';
  EXPECT_TRUE(ErrorMentions(DecodeFrame(frame), "identifier"));
}

TEST(ProtocolMalformedTest, PrefixThatDisagreesWithTheBufferIsRejected) {
  std::vector<uint8_t> frame = EncodeFrame(CancelMsg{1});
  frame.push_back(0);
  EXPECT_TRUE(ErrorMentions(DecodeFrame(frame), "length prefix says"));
}

TEST(ProtocolMalformedTest, FrameAboveACustomLimitIsRejected) {
  const std::vector<uint8_t> frame =
      EncodeFrame(testing::SampleOf<SceneChunkMsg>());  // 300 B of data
  EXPECT_TRUE(DecodeFrame(frame, 4096));
  EXPECT_TRUE(ErrorMentions(DecodeFrame(frame, 64), "exceeds the limit"));
}

// Hand-made FlatBuffers for what EncodeFrame cannot produce.
std::vector<uint8_t> Finish(flatbuffers::FlatBufferBuilder& fbb,
                            flatbuffers::Offset<wire::Frame> frame) {
  wire::FinishFrameBuffer(fbb, frame);
  return WithPrefix(fbb.GetBufferPointer(), fbb.GetSize());
}

TEST(ProtocolMalformedTest, UnknownMessageTypeIsRejected) {
  flatbuffers::FlatBufferBuilder fbb;
  const auto cancel = wire::CreateCancel(fbb, 5).Union();
  const auto frame = wire::CreateFrame(fbb, 1, static_cast<wire::Payload>(200), cancel);
  EXPECT_TRUE(ErrorMentions(DecodeFrame(Finish(fbb, frame)), "unknown message type 200"));
}

TEST(ProtocolMalformedTest, MissingPayloadIsRejected) {
  flatbuffers::FlatBufferBuilder fbb;
  wire::FrameBuilder builder(fbb);
  builder.add_version(1);
  const auto frame = builder.Finish();  // no payload, though it is required
  EXPECT_FALSE(DecodeFrame(Finish(fbb, frame)));
}

TEST(ProtocolMalformedTest, MissingRequiredFieldIsRejected) {
  flatbuffers::FlatBufferBuilder fbb;
  wire::HelloBuilder hello(fbb);  // no name, no nonce
  hello.add_min_version(1);
  hello.add_max_version(1);
  hello.add_threads(4);
  const auto payload = hello.Finish().Union();
  const auto frame = wire::CreateFrame(fbb, 1, wire::Payload::Hello, payload);
  EXPECT_TRUE(ErrorMentions(DecodeFrame(Finish(fbb, frame)), "verifier"));
}

TEST(ProtocolMalformedTest, PayloadOfTheWrongTableTypeIsRejected) {
  // A Cancel table labelled as a LeaseResult: its required fields are missing.
  flatbuffers::FlatBufferBuilder fbb;
  const auto cancel = wire::CreateCancel(fbb, 5).Union();
  const auto frame = wire::CreateFrame(fbb, 1, wire::Payload::LeaseResult, cancel);
  EXPECT_FALSE(DecodeFrame(Finish(fbb, frame)));
}

// Version 1's BatchAssignment and BatchResult keep their union slots as empty tables, so later
// messages keep their numbers; a frame in either slot is refused by name, in any version and
// whatever table it carries.
TEST(ProtocolMalformedTest, FramesInRetiredSlotsAreRefused) {
  struct Slot {
    wire::Payload type;
    const char* name;
  };
  for (const Slot slot : {Slot{wire::Payload::RetiredBatchAssignment, "BatchAssignment"},
                          Slot{wire::Payload::RetiredBatchResult, "BatchResult"}}) {
    const std::string expected = std::to_string(static_cast<unsigned>(slot.type)) + " (" +
                                 slot.name + ", protocol version 1) is retired";
    for (uint16_t version : {uint16_t{1}, kProtocolVersion}) {
      flatbuffers::FlatBufferBuilder fbb;
      const auto empty = slot.type == wire::Payload::RetiredBatchAssignment
                             ? wire::CreateRetiredBatchAssignment(fbb).Union()
                             : wire::CreateRetiredBatchResult(fbb).Union();
      EXPECT_TRUE(ErrorMentions(
          DecodeFrame(Finish(fbb, wire::CreateFrame(fbb, version, slot.type, empty))), expected))
          << slot.name << " in version " << version;
    }
    // An old peer's table in the slot (here a Cancel's) is refused just the same.
    flatbuffers::FlatBufferBuilder fbb;
    const auto cancel = wire::CreateCancel(fbb, 5).Union();
    EXPECT_TRUE(ErrorMentions(
        DecodeFrame(Finish(fbb, wire::CreateFrame(fbb, 1, slot.type, cancel))), expected))
        << slot.name;
  }
  EXPECT_EQ(static_cast<unsigned>(wire::Payload::LeaseReturn),
            8u);  // the next slot kept its number
}

// A LeaseResult's hits are structs up to version 4 and packed from version 5 (core/packed_hits.h):
// the frame's own version says which, and the other form is refused by name.
std::vector<uint8_t> HandMadeLeaseResult(uint16_t version, uint32_t hit_count,
                                         const std::vector<wire::PatchHit>& hits,
                                         const std::vector<uint8_t>* packed) {
  flatbuffers::FlatBufferBuilder fbb;
  const wire::BatchTally tally(wire::LeaseRef(1, 2, 3), 0, 0, 0, 0, 0.5, hit_count);
  const auto batches = fbb.CreateVectorOfStructs(&tally, 1);
  const auto structs = fbb.CreateVectorOfStructs(hits.data(), hits.size());
  const auto packed_hits = packed != nullptr ? fbb.CreateVector(*packed) : 0;
  const auto result = wire::CreateLeaseResult(fbb, batches, structs, packed_hits).Union();
  return Finish(fbb, wire::CreateFrame(fbb, version, wire::Payload::LeaseResult, result));
}

TEST(ProtocolMalformedTest, ALeaseResultsHitsMustBeInItsVersionsForm) {
  const std::vector<wire::PatchHit> structs = {{4, 1}, {9, 2}};
  const std::vector<uint8_t> packed = {4, 1, 5, 2};  // the same two hits
  const std::vector<uint8_t> none;
  EXPECT_TRUE(DecodeFrame(HandMadeLeaseResult(4, 2, structs, nullptr)));
  EXPECT_TRUE(DecodeFrame(HandMadeLeaseResult(5, 2, {}, &packed)));
  const std::vector<uint8_t> repeated = {4, 1, 0, 2}, weightless = {4, 0}, cut = {4, 0x81};
  struct Refused {
    uint16_t version;
    uint32_t hit_count;
    bool structs;
    const std::vector<uint8_t>* packed;
    const char* error;
  };
  for (const Refused& r : std::vector<Refused>{
           {5, 2, true, nullptr, "LeaseResult: missing packed_hits (version 5 on)"},
           {5, 2, true, &packed, "hits in version-4 form in a version-5 frame"},
           {4, 2, true, &packed, "packed_hits in a version-4 frame"},
           // Packed hits must hold exactly the batches' counts, in patch order, with weights.
           {5, 1, false, &packed, "2 bytes of packed hits after the last batch's"},
           {5, 3, false, &packed, "batch 0's packed hits: 4 bytes cannot hold 3 hits"},
           {5, 1, false, &none, "0 bytes cannot hold 1 hits"},
           {5, 2, false, &repeated, "hit 1 is out of patch order or has no weight"},
           {5, 1, false, &weightless, "hit 0 is out of patch order or has no weight"},
           {5, 1, false, &cut, "hit 0 ends inside a number"},
       }) {
    const std::vector<wire::PatchHit> hits = r.structs ? structs : std::vector<wire::PatchHit>{};
    EXPECT_TRUE(ErrorMentions(
        DecodeFrame(HandMadeLeaseResult(r.version, r.hit_count, hits, r.packed)), r.error))
        << r.error;
  }
}

TEST(ProtocolMalformedTest, DeeplyNestedOrHugeVectorsAreBounded) {
  // A LeaseResult whose hits vector (version 4: structs) claims more elements than the buffer
  // holds.
  std::vector<uint8_t> frame =
      EncodeFrame(LeaseResultMsg{{BatchOutcome{{}, {{1, 1}, {2, 1}}, 0, 0, 0, 0, 0}}}, 4);
  // Find the vector length word (2) followed by the first hit (patch 1) and inflate it.
  bool patched = false;
  for (size_t i = kLengthPrefixBytes; i + 4 <= frame.size() && !patched; ++i) {
    if (ReadLengthPrefix(&frame[i]) == 2 && i + 8 <= frame.size() &&
        ReadLengthPrefix(&frame[i + 4]) == 1) {
      frame[i + 3] = 0x10;
      patched = true;
    }
  }
  ASSERT_TRUE(patched);
  EXPECT_FALSE(DecodeFrame(frame));
}

}  // namespace
}  // namespace radfarm::protocol
