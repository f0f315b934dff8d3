#include "daemon/agents/agent_link.h"

#include <chrono>

#include "base/result.h"
#include "loop/log.h"

namespace radfarm::daemon {
namespace {

int64_t UnixMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

AgentLink::AgentLink(loop::EventLoop& loop, const Clock& clock,
                     std::unique_ptr<loop::FramedConnection> connection,
                     const protocol::FarmSecret& secret,
                     const protocol::MasterConfig& session_config, const AgentLinkOptions& options,
                     Callbacks callbacks)
    : clock_(clock),
      connection_(std::move(connection)),
      session_(protocol::ProtocolSession::ForMaster(secret, session_config)),
      options_(options),
      callbacks_(std::move(callbacks)),
      handshake_deadline_(loop),
      id_(session_config.agent_id),
      address_(connection_->peer()) {}

std::string AgentLink::Describe() const {
  if (!was_authenticated_) return address_;
  return name() + "@" + address_ + " (agent " + std::to_string(id_) + ")";
}

void AgentLink::Start() {
  last_heard_ms_ = clock_.NowMs();
  loop::ConnectionOptions options;
  options.max_frame_bytes = options_.max_frame_bytes;
  options.frame_budget = options_.frame_budget;
  connection_->Start(
      options, [this](std::span<const uint8_t> payload) { OnFrame(payload); },
      [this](const std::string& reason) {
        handshake_deadline_.Close();
        callbacks_.on_closed(*this, reason);  // may destroy *this
      });
  connection_->SetMaxReceiveFrameBytes(protocol::kMaxHandshakeFrameBytes);
  handshake_deadline_.Start(options_.handshake_timeout, [this] {
    if (authenticated() || closing_) return;
    session_.Abort("handshake timeout");
    Fail("handshake not finished within " + std::to_string(options_.handshake_timeout.count()) +
         " ms");
  });
}

Status AgentLink::Send(const protocol::Message& message) {
  if (closing_) return Error{"connection to " + Describe() + " is closing"};
  Result<std::vector<uint8_t>> frame = session_.Encode(message);
  RADFARM_RETURN_IF_ERROR(frame);
  return connection_->SendPrefixed(std::move(*frame));
}

void AgentLink::Close(protocol::CloseCode code, const std::string& reason) {
  if (closing_) return;
  if (session_.state() != protocol::ProtocolSession::State::kClosed) {
    (void)Send(protocol::CloseMsg{code, reason.substr(0, protocol::kMaxCloseDetailBytes)});
  }
  closing_ = true;
  connection_->CloseAfterFlush(reason);
}

void AgentLink::Drop(const std::string& reason) {
  if (closing_) return;
  closing_ = true;
  session_.Abort(reason);
  connection_->Close(reason);
}

void AgentLink::Fail(const std::string& reason) {
  if (closing_) return;
  closing_ = true;
  (void)connection_->SendPrefixed(session_.CloseFrame());
  connection_->CloseAfterFlush(reason);
}

void AgentLink::OnFrame(std::span<const uint8_t> payload) {
  if (closing_) return;
  last_heard_ms_ = clock_.NowMs();
  // Decode opens sealed frames: a frame that fails authentication is the wire's fault (or an
  // attacker's), not the agent's, so it only ends this connection; the agent may reconnect.
  Result<protocol::DecodedFrame> frame = session_.Decode(payload);
  if (!frame) {
    if (was_authenticated_) {
      loop::LogLine(loop::LogLevel::kWarning, "agents")
          << Describe() << ": " << frame.error() << "; closing the connection";
    }
    Fail(frame.error());
    return;
  }
  const bool was_authenticated = session_.authenticated();
  Result<protocol::ProtocolSession::Accepted> accepted = session_.Accept(*frame);
  if (!accepted) {
    if (was_authenticated) {
      loop::LogLine(loop::LogLevel::kWarning, "agents")
          << Describe() << ": protocol error: " << accepted.error() << "; closing";
    }
    Fail((was_authenticated ? "" : "refused: ") + accepted.error());
    return;
  }
  if (!accepted->reply.empty()) (void)connection_->SendPrefixed(std::move(accepted->reply));
  if (!was_authenticated && session_.authenticated()) {
    handshake_deadline_.Stop();
    was_authenticated_ = true;
    connection_->SetMaxReceiveFrameBytes(options_.max_frame_bytes);
    connected_unix_ms_ = UnixMs();
    connection_->SetReadIdleTimeout(options_.idle_close_timeout);
    callbacks_.on_authenticated(*this);
    return;
  }
  if (!accepted->deliver) return;
  if (auto* close = std::get_if<protocol::CloseMsg>(&frame->message)) {
    loop::LogLine(loop::LogLevel::kInfo, "agents")
        << Describe() << " closed the connection: " << protocol::CloseCodeName(close->code)
        << (close->detail.empty() ? "" : " (" + close->detail + ")");
    closing_ = true;
    connection_->CloseAfterFlush("closed by the agent");
    return;
  }
  callbacks_.on_message(*this, frame->message);
}

}  // namespace radfarm::daemon
