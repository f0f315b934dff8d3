// Raw sockets for the door tests: what a stranger or a broken client does to radfarmd's ports,
// below the CLI and the agent (junk frames, announced lengths that never come, silence).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace radfarm::testing {

// Connected sockets, or -1. Blocking; the caller closes them.
int ConnectUnixSocket(const std::string& path);
int ConnectTcpSocket(const std::string& host_port);  // "127.0.0.1:PORT"

// The 4-byte little-endian length prefix of a frame.
std::string FramePrefix(uint32_t payload_bytes);
std::string Frame(std::string_view payload);

// Writes what it can without blocking; false if the socket refused every byte.
bool SendSome(int fd, std::string_view bytes);
// Reads one frame's payload within `timeout`; nullopt if the peer closed or went silent.
std::optional<std::string> ReadFramePayload(int fd, std::chrono::milliseconds timeout);
// Reads and drops until the peer closes (true) or `timeout` passes (false).
bool WaitForPeerClose(int fd, std::chrono::milliseconds timeout);

}  // namespace radfarm::testing
