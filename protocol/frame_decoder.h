// FrameDecoder: cuts a byte stream (TCP, as libuv delivers it: any chunk sizes) into verified
// frames. Feed() whatever arrived, then call Next() until it yields nothing:
//
//   if (Status s = decoder.Feed(chunk); !s) return CloseWith(s.error());
//   for (;;) {
//     Result<std::optional<DecodedFrame>> next = decoder.Next();
//     if (!next) return CloseWith(next.error());   // malformed: drop the connection
//     if (!*next) break;                            // need more bytes
//     Handle(std::move(**next));
//   }
//
// The length prefix is checked against the limit as soon as its 4 bytes are in, before anything is
// reserved for the frame, so a peer cannot make us allocate more than it actually sends. After
// the first error the decoder stays failed: a byte stream cannot be resynchronised.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/result.h"
#include "protocol/limits.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

class FrameDecoder {
 public:
  explicit FrameDecoder(uint32_t max_frame_bytes = kDefaultMaxFrameBytes);

  // Appends bytes. Fails only if the decoder already failed.
  Status Feed(std::span<const uint8_t> bytes);

  // The next complete frame, nullopt if its bytes are not all in yet, or the reason the stream is
  // malformed (oversized or undersized length, bad FlatBuffer, bad values).
  Result<std::optional<DecodedFrame>> Next();

  // The next complete frame's bytes after its length prefix, undecoded (the length checked as
  // for Next()): for a sealed frame, which ProtocolSession::Decode opens and decodes.
  Result<std::optional<std::vector<uint8_t>>> NextBody();

  // Bytes received but not yet returned as frames.
  size_t buffered_bytes() const { return buffer_.size() - read_; }
  bool failed() const { return !error_.empty(); }

 private:
  Error Fail(std::string reason);

  uint32_t max_frame_bytes_;
  std::vector<uint8_t> buffer_;
  size_t read_ = 0;  // start of the first unreturned frame in buffer_
  std::string error_;
};

}  // namespace radfarm::protocol
