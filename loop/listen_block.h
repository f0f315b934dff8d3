// Internal to loop/: the listening socket shared by TcpListener and UnixListener (handle_block.h
// explains the block). Accepts each pending connection into a FramedConnection and hands it to
// on_connection on the loop thread; accept errors (a connection refused for want of descriptors
// among them: framed_connection.cc) are logged, rate-limited, and the listener carries on.
#pragma once

#include <uv.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "base/log_rate_limiter.h"
#include "base/result.h"
#include "loop/framed_connection.h"
#include "loop/handle_block.h"

namespace radfarm::loop::internal {

inline constexpr uint32_t kAcceptLogLines = 5;
inline constexpr std::chrono::seconds kAcceptLogWindow{10};

struct ListenBlock : HandleBlock {
  using OnConnection = std::function<void(std::unique_ptr<FramedConnection>)>;

  ListenBlock(uv_loop_t* loop, bool unix, OnConnection callback);

  uv_stream_t* stream() { return reinterpret_cast<uv_stream_t*>(&tcp); }
  Status Listen();

  // Runs from BeginClose (OnClosing), once.
  std::function<void()> on_closing;

  union {
    uv_tcp_t tcp;
    uv_pipe_t pipe;
  };
  const bool unix_socket;
  std::string name;  // the bound address or path, for logs and peers
  OnConnection on_connection;
  // Accept failures (out of descriptors, most often) come in floods: at most so many lines.
  LogRateLimiter accept_log{kAcceptLogLines, kAcceptLogWindow};

 private:
  void OnClosing() override;
  void LogAcceptFailure(const std::string& text);
  static void OnConnectionReady(uv_stream_t* server, int status) noexcept;
};

}  // namespace radfarm::loop::internal
