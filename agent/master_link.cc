#include "agent/master_link.h"

#include <algorithm>
#include <variant>

#include "base/result.h"
#include "protocol/limits.h"

namespace radfarm::agent {
namespace {

// Silence after which the master is taken as gone: 4 heartbeat intervals.
std::chrono::milliseconds SilenceLimit(uint32_t heartbeat_interval_ms) {
  return std::chrono::milliseconds(uint64_t{4} * heartbeat_interval_ms);
}

}  // namespace

MasterLink::MasterLink(const protocol::FarmSecret& secret, const protocol::AgentConfig& config,
                       Callbacks callbacks)
    : session_(protocol::ProtocolSession::ForAgent(secret, config)),
      callbacks_(std::move(callbacks)) {}

MasterLink::~MasterLink() = default;

Result<std::unique_ptr<MasterLink>> MasterLink::Connect(loop::EventLoop& loop,
                                                        const loop::SocketAddress& address,
                                                        const protocol::FarmSecret& secret,
                                                        const protocol::AgentConfig& config,
                                                        Timing timing, Callbacks callbacks) {
  std::unique_ptr<MasterLink> link(new MasterLink(secret, config, std::move(callbacks)));
  MasterLink* self = link.get();
  loop::ConnectionOptions options;
  options.max_frame_bytes = protocol::kDefaultMaxFrameBytes;
  options.read_idle_timeout = timing.handshake_timeout;
  options.flush_timeout = timing.flush_timeout;
  Result<std::unique_ptr<loop::FramedConnection>> connection = loop::FramedConnection::ConnectTcp(
      loop, address, options, [self](std::span<const uint8_t> payload) { self->OnFrame(payload); },
      [self](const std::string& reason) { self->OnClose(reason); },
      [self] { self->OnConnected(); });
  RADFARM_RETURN_IF_ERROR(connection);
  link->connection_ = std::move(connection).value();
  link->peer_ = link->connection_->peer();
  return link;
}

void MasterLink::OnConnected() {
  Result<std::vector<uint8_t>> hello = session_.Start();
  if (!hello) {
    FailWith("cannot start the handshake: " + hello.error());
    return;
  }
  if (Status sent = connection_->SendPrefixed(std::move(hello).value()); !sent) {
    connection_->Close(sent.error());
  }
}

void MasterLink::OnFrame(std::span<const uint8_t> payload) {
  if (session_.state() == protocol::ProtocolSession::State::kClosed) return;
  Result<protocol::DecodedFrame> frame = session_.Decode(payload);
  if (!frame) {
    FailWith("bad frame from the master: " + frame.error());
    return;
  }
  const bool was_authenticated = session_.authenticated();
  Result<protocol::ProtocolSession::Accepted> accepted = session_.Accept(*frame);
  if (!accepted) {
    auth_failed_ = session_.failure_code() == protocol::CloseCode::kAuthFailed;
    FailWith(accepted.error());
    return;
  }
  if (!accepted->reply.empty()) {
    if (Status sent = connection_->SendPrefixed(std::move(accepted->reply)); !sent) return;
  }
  if (const auto& close = session_.peer_close(); close && accepted->deliver) {
    auth_failed_ = close->code == protocol::CloseCode::kAuthFailed;
    blocklisted_ = close->code == protocol::CloseCode::kBlocklisted;
    refused_ = was_authenticated_ && !heard_after_welcome_ && !auth_failed_ && !blocklisted_;
    close_reason_ =
        "the master closed the connection: " + std::string(protocol::CloseCodeName(close->code)) +
        (close->detail.empty() ? "" : " (" + close->detail + ")");
    connection_->Close(close_reason_);
    return;
  }
  if (!was_authenticated && session_.authenticated()) {
    was_authenticated_ = true;
    connection_->SetReadIdleTimeout(SilenceLimit(session_.welcome().heartbeat_interval_ms));
    if (callbacks_.on_authenticated) callbacks_.on_authenticated(session_.welcome());
    return;
  }
  if (!accepted->deliver) return;
  heard_after_welcome_ = true;
  if (callbacks_.on_message) callbacks_.on_message(frame->message);
}

void MasterLink::FailWith(const std::string& reason) {
  close_reason_ = reason;
  (void)connection_->SendPrefixed(session_.CloseFrame());
  connection_->CloseAfterFlush(reason);
}

void MasterLink::OnClose(const std::string& reason) {
  LinkClosed closed;
  closed.reason = close_reason_.empty() ? reason : close_reason_;
  closed.auth_failed = auth_failed_;
  closed.blocklisted = blocklisted_;
  closed.was_authenticated = was_authenticated_;
  closed.refused = refused_;
  std::function<void(const LinkClosed&)> on_closed = std::move(callbacks_.on_closed);
  if (on_closed) on_closed(closed);  // last: it may destroy this link
}

Status MasterLink::Send(const protocol::Message& message) {
  if (connection_->state() != loop::HandleState::kOpen) {
    return Error{"connection to " + peer_ + " is closing"};
  }
  Result<std::vector<uint8_t>> frame = session_.Encode(message);
  RADFARM_RETURN_IF_ERROR(frame);
  return connection_->SendPrefixed(std::move(frame).value());
}

void MasterLink::Close(protocol::CloseCode code, const std::string& detail) {
  if (connection_->state() != loop::HandleState::kOpen) return;
  if (close_reason_.empty()) close_reason_ = "closed by the agent: " + detail;
  if (session_.state() != protocol::ProtocolSession::State::kClosed) {
    Result<std::vector<uint8_t>> frame = session_.Encode(protocol::CloseMsg{code, detail});
    if (frame) (void)connection_->SendPrefixed(std::move(frame).value());
  }
  connection_->CloseAfterFlush(close_reason_);
}

void MasterLink::Disconnect(const std::string& reason) {
  if (connection_->state() != loop::HandleState::kOpen) return;
  if (close_reason_.empty()) close_reason_ = reason;
  connection_->CloseAfterFlush(close_reason_);
}

}  // namespace radfarm::agent
