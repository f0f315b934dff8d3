// Frames on the control socket (docs/CONTROL.md): a little-endian uint32 payload length, then the
// payload. Blocking I/O on a stream socket whose timeouts (SO_RCVTIMEO, SO_SNDTIMEO) bound every
// call; a timeout is an error like any other.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"

namespace radfarm {

inline constexpr uint32_t kMaxJsonFrameBytes = uint32_t{1} << 20;   // 1 MiB
inline constexpr uint32_t kMaxAttachmentBytes = uint32_t{1} << 30;  // 1 GiB

// Sends the length prefix and the whole payload. Never raises SIGPIPE: a closed peer is an error.
Status WriteFrame(int fd, std::span<const uint8_t> payload);

// Reads one whole frame. A payload longer than `max_bytes` is refused before it is read. The peer
// closing the connection before or inside a frame is an error.
Result<std::vector<uint8_t>> ReadFrame(int fd, uint32_t max_bytes);

}  // namespace radfarm
