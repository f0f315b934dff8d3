#include "cli/control_frames.h"

#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "base/result.h"

namespace radfarm {
namespace {

std::string SocketErrorText(int error) {
  if (error == EAGAIN || error == EWOULDBLOCK) return "timed out";
  return std::strerror(error);
}

Status SendAll(int fd, const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t sent = ::send(fd, data, size, MSG_NOSIGNAL);
    if (sent < 0) {
      if (errno == EINTR) continue;
      return Error{"send: " + SocketErrorText(errno)};
    }
    data += sent;
    size -= size_t(sent);
  }
  return Ok{};
}

// Reads exactly `size` bytes; `what` names them in the error when the peer closes first.
Status ReceiveAll(int fd, uint8_t* data, size_t size, const char* what) {
  while (size > 0) {
    const ssize_t got = ::recv(fd, data, size, 0);
    if (got < 0) {
      if (errno == EINTR) continue;
      return Error{"receive: " + SocketErrorText(errno)};
    }
    if (got == 0) return Error{std::string("connection closed by the master inside ") + what};
    data += got;
    size -= size_t(got);
  }
  return Ok{};
}

}  // namespace

Status WriteFrame(int fd, std::span<const uint8_t> payload) {
  if (payload.size() > kMaxAttachmentBytes) {
    return Error{"a frame of " + std::to_string(payload.size()) + " bytes is over the " +
                 std::to_string(kMaxAttachmentBytes) + "-byte limit"};
  }
  const uint32_t n = uint32_t(payload.size());
  const uint8_t prefix[4] = {uint8_t(n), uint8_t(n >> 8), uint8_t(n >> 16), uint8_t(n >> 24)};
  RADFARM_RETURN_IF_ERROR(SendAll(fd, prefix, sizeof prefix));
  return SendAll(fd, payload.data(), payload.size());
}

Result<std::vector<uint8_t>> ReadFrame(int fd, uint32_t max_bytes) {
  uint8_t prefix[4];
  // A close before the first byte of a frame is the common case worth its own words.
  for (;;) {
    const ssize_t got = ::recv(fd, prefix, 1, 0);
    if (got == 1) break;
    if (got == 0) return Error{"the master closed the connection without answering"};
    if (errno != EINTR) return Error{"receive: " + SocketErrorText(errno)};
  }
  RADFARM_RETURN_IF_ERROR(ReceiveAll(fd, prefix + 1, 3, "a frame's length"));
  const uint32_t n = uint32_t(prefix[0]) | uint32_t(prefix[1]) << 8 | uint32_t(prefix[2]) << 16 |
                     uint32_t(prefix[3]) << 24;
  if (n > max_bytes) {
    return Error{"a frame of " + std::to_string(n) + " bytes, over the " +
                 std::to_string(max_bytes) + "-byte limit"};
  }
  std::vector<uint8_t> payload(n);
  RADFARM_RETURN_IF_ERROR(ReceiveAll(fd, payload.data(), n, "a frame"));
  return payload;
}

}  // namespace radfarm
