// One frame = a 4-byte little-endian length prefix + one FlatBuffer (schema/frame.fbs, identifier
// "RDFM") holding the protocol version and one message. This file turns messages into frames and
// back; frame_decoder.h cuts a byte stream into frames.
#pragma once

#include <cstddef>
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

// An agent cuts a lease's results into LeaseResult frames of about this many bytes: the master's
// connection reads a frame that size without growing its buffer past what it keeps between frames
// (loop/frame_splitter.cc), where frames of a MiB cost it a fresh, page-faulting buffer each, a
// large share of the master's CPU.
inline constexpr size_t kResultFrameBytes = 60 * 1024;

// About what one batch's result adds to a LeaseResult frame of `version`: its counts (~72 bytes)
// and its hits, packed from kPackedHitsVersion on (2-3 bytes a hit), 16 bytes a hit before.
size_t ResultFrameCost(const BatchOutcome& result, uint16_t version);

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
