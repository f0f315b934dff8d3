// One frame = a 4-byte little-endian length prefix + one FlatBuffer (schema/frame.fbs, identifier
// "RDFM") holding the protocol version and one message. This file turns messages into frames and
// back; frame_decoder.h cuts a byte stream into frames.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "protocol/limits.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

// The whole frame, prefix included, written in protocol `version`. Does not check the values:
// ProtocolSession::Encode runs CheckMessage first, so a session never sends what its peer would
// reject. (Tests use this directly to make bad frames.)
std::vector<uint8_t> EncodeFrame(const Message& message, uint16_t version = kProtocolVersion);

// Checks a length prefix before anything is allocated for the frame: 0 < length, kMinFrameBytes
// <= length <= max_frame_bytes.
Status CheckFrameLength(uint32_t length, uint32_t max_frame_bytes);

uint32_t ReadLengthPrefix(const uint8_t* bytes);

// Decodes the bytes after a length prefix: file identifier, FlatBuffers verifier (bounds, depth,
// alignment), a known message type, version >= 1, every required field present, then
// CheckMessage. Any byte string is safe to pass; it never reads outside `body`.
Result<DecodedFrame> DecodeFrameBody(std::span<const uint8_t> body);

// Decodes a buffer that holds exactly one whole frame, prefix included.
Result<DecodedFrame> DecodeFrame(std::span<const uint8_t> frame,
                                 uint32_t max_frame_bytes = kDefaultMaxFrameBytes);

}  // namespace radfarm::protocol
