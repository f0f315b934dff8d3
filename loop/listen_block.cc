#include "loop/listen_block.h"

#include <sys/socket.h>

#include <optional>
#include <string>

#include "loop/check.h"
#include "loop/log.h"
#include "loop/uv_error.h"

namespace radfarm::loop::internal {

ListenBlock::ListenBlock(uv_loop_t* loop, bool unix, OnConnection callback)
    : unix_socket(unix), on_connection(std::move(callback)) {
  LOOP_CHECK((unix ? uv_pipe_init(loop, &pipe, 0) : uv_tcp_init(loop, &tcp)) == 0);
  Adopt(&tcp);  // a union: the same address whichever member is live
}

Status ListenBlock::Listen() {
  if (int rc = uv_listen(stream(), SOMAXCONN, &OnConnectionReady); rc < 0) {
    return UvError("listen on " + name, rc);
  }
  return Ok{};
}

void ListenBlock::OnClosing() {
  if (on_closing) on_closing();
}

void ListenBlock::LogAcceptFailure(const std::string& text) {
  const auto now = std::chrono::steady_clock::now();
  const std::optional<uint64_t> held_back = accept_log.TakeSuppressed(now);  // a past window's
  if (!accept_log.Allow(now)) return;
  Log(LogLevel::kWarning, "loop",
      held_back ? text + " (and " + std::to_string(*held_back) + " more not logged before it)"
                : text);
}

void ListenBlock::OnConnectionReady(uv_stream_t* server, int status) noexcept {
  auto* block = Of<ListenBlock>(server);
  if (status < 0) {
    block->LogAcceptFailure(UvErrorText("incoming connection on " + block->name, status));
    return;
  }
  Result<std::unique_ptr<FramedConnection>> connection =
      FramedConnection::Accept(server, block->unix_socket, block->name);
  if (!connection.ok()) {
    block->LogAcceptFailure(connection.error());
    return;
  }
  block->on_connection(std::move(connection).value());  // may close or destroy the listener
}

}  // namespace radfarm::loop::internal
