#include "protocol/frame_codec.h"

#include <cstring>
#include <string>

#include "base/result.h"
#include "core/packed_hits.h"
#include "protocol/message_checks.h"
#include "protocol/wire_convert.h"

namespace radfarm::protocol {
namespace {

// A frame holds two tables (Frame and its payload) and a vector or two; anything deeper or
// bigger is not ours.
constexpr flatbuffers::uoffset_t kMaxDepth = 8;
constexpr flatbuffers::uoffset_t kMaxTables = 16;

// FlatBuffers reads scalars in place, so the buffer must start on an 8-byte boundary (alignment
// inside it is the verifier's job).
constexpr size_t kBufferAlignment = 8;

Result<DecodedFrame> DecodeAligned(const uint8_t* data, size_t size) {
  if (!flatbuffers::BufferHasIdentifier(data, wire::FrameIdentifier())) {
    return Error{"frame: not a radfarm frame (wrong file identifier)"};
  }
  flatbuffers::Verifier verifier(data, size, kMaxDepth, kMaxTables);
  if (!wire::VerifyFrameBuffer(verifier)) {
    return Error{"frame: malformed FlatBuffer (verifier failed)"};
  }
  const wire::Frame* frame = wire::GetFrame(data);
  if (frame->version() < 1) return Error{"frame: protocol version 0"};
  Result<Message> message = ReadPayload(*frame);
  RADFARM_RETURN_IF_ERROR(message);
  RADFARM_RETURN_IF_ERROR(CheckMessage(*message));
  return DecodedFrame{frame->version(), std::move(message).value()};
}

}  // namespace

std::vector<uint8_t> EncodeFrame(const Message& message, uint16_t version) {
  flatbuffers::FlatBufferBuilder fbb(256);
  wire::Payload type = wire::Payload::NONE;
  const flatbuffers::Offset<void> payload = BuildPayload(fbb, message, version, &type);
  wire::FinishFrameBuffer(fbb, wire::CreateFrame(fbb, version, type, payload));
  const uint32_t size = fbb.GetSize();
  std::vector<uint8_t> out(kLengthPrefixBytes + size);
  for (size_t i = 0; i < kLengthPrefixBytes; ++i) out[i] = static_cast<uint8_t>(size >> (8 * i));
  std::memcpy(out.data() + kLengthPrefixBytes, fbb.GetBufferPointer(), size);
  return out;
}

size_t ResultFrameCost(const BatchOutcome& result, uint16_t version) {
  return 96 +
         (version >= kPackedHitsVersion ? PackedHitsBytes(result.hits) : 16 * result.hits.size());
}

uint32_t ReadLengthPrefix(const uint8_t* bytes) {
  return uint32_t{bytes[0]} | uint32_t{bytes[1]} << 8 | uint32_t{bytes[2]} << 16 |
         uint32_t{bytes[3]} << 24;
}

Status CheckFrameLength(uint32_t length, uint32_t max_frame_bytes) {
  if (length > max_frame_bytes) {
    return Error{"frame: length " + std::to_string(length) + " exceeds the limit of " +
                 std::to_string(max_frame_bytes) + " bytes"};
  }
  if (length < kMinFrameBytes) {
    return Error{"frame: length " + std::to_string(length) + " is too short for a frame"};
  }
  return Ok{};
}

Result<DecodedFrame> DecodeFrameBody(std::span<const uint8_t> body) {
  if (body.size() < kMinFrameBytes) {
    return Error{"frame: " + std::to_string(body.size()) + " bytes is too short for a frame"};
  }
  if (reinterpret_cast<uintptr_t>(body.data()) % kBufferAlignment == 0) {
    return DecodeAligned(body.data(), body.size());
  }
  std::vector<uint64_t> aligned((body.size() + 7) / 8);
  std::memcpy(aligned.data(), body.data(), body.size());
  return DecodeAligned(reinterpret_cast<const uint8_t*>(aligned.data()), body.size());
}

Result<DecodedFrame> DecodeFrame(std::span<const uint8_t> frame, uint32_t max_frame_bytes) {
  if (frame.size() < kLengthPrefixBytes) return Error{"frame: truncated length prefix"};
  const uint32_t length = ReadLengthPrefix(frame.data());
  RADFARM_RETURN_IF_ERROR(CheckFrameLength(length, max_frame_bytes));
  if (frame.size() - kLengthPrefixBytes != length) {
    return Error{"frame: length prefix says " + std::to_string(length) + " bytes but " +
                 std::to_string(frame.size() - kLengthPrefixBytes) + " follow"};
  }
  return DecodeFrameBody(frame.subspan(kLengthPrefixBytes));
}

}  // namespace radfarm::protocol
