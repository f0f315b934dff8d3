// AgentLink: the master's end of one agent connection. It runs the handshake (ProtocolSession),
// enforces its deadline, checks every frame (ProtocolSession::Decode: opened once sealed, then
// DecodeFrameBody; then the session's state and direction rules) and hands authenticated
// application messages to the master. Any protocol error closes this one connection only. After the
// handshake it is logged here with the agent's name; before it, the reason goes to on_closed alone
// and the master logs it rate-limited (a stranger's junk must not flood the journal). Until it
// authenticates, the peer's frames may be at most protocol::kMaxHandshakeFrameBytes long.
//
// Lifecycle:  accepted --Hello..Welcome--> authenticated --Close/error/EOF/idle--> closed
//             accepted --deadline, bad proof, malformed frame--> closed
// on_closed runs once, after the socket is closed; it may destroy the link. Loop thread only.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "daemon/jobs/clock.h"
#include "loop/event_loop.h"
#include "loop/frame_budget.h"
#include "loop/framed_connection.h"
#include "loop/timer.h"
#include "protocol/farm_secret.h"
#include "protocol/messages.h"
#include "protocol/protocol_session.h"

namespace radfarm::daemon {

struct AgentLinkOptions {
  std::chrono::milliseconds handshake_timeout{5000};
  // After the handshake: a peer silent this long is closed (the master takes its leases away
  // much earlier, after agent_timeout; this frees the socket of a peer that never comes back).
  std::chrono::milliseconds idle_close_timeout{30000};
  uint32_t max_frame_bytes = protocol::kDefaultMaxFrameBytes;
  // What every agent's unfinished frames may hold together (--max-frame-bytes-held).
  std::shared_ptr<loop::FrameBudget> frame_budget;
};

class AgentLink {
 public:
  struct Callbacks {
    std::function<void(AgentLink&)> on_authenticated;
    std::function<void(AgentLink&, protocol::Message&)> on_message;  // application messages
    std::function<void(AgentLink&, const std::string& reason)> on_closed;
  };

  AgentLink(loop::EventLoop& loop, const Clock& clock,
            std::unique_ptr<loop::FramedConnection> connection, const protocol::FarmSecret& secret,
            const protocol::MasterConfig& session_config, const AgentLinkOptions& options,
            Callbacks callbacks);
  AgentLink(const AgentLink&) = delete;
  AgentLink& operator=(const AgentLink&) = delete;

  // Starts reading and the handshake deadline.
  void Start();
  // Encodes through the session (which refuses what the agent would reject) and queues it.
  Status Send(const protocol::Message& message);
  // Sends a Close with `code` and `reason`, then closes once it is flushed.
  void Close(protocol::CloseCode code, const std::string& reason);
  // Closes at once, sending nothing: for a stranger that must make room (DoorKeeper).
  void Drop(const std::string& reason);

  uint64_t id() const { return id_; }
  bool authenticated() const { return session_.authenticated(); }
  // Whether the handshake ever succeeded (still true after a Close ended the session).
  bool was_authenticated() const { return was_authenticated_; }
  bool closing() const { return closing_; }
  const std::string& address() const { return address_; }
  // The agent's name and threads (from its Hello), once authenticated.
  const std::string& name() const { return session_.hello().agent_name; }
  uint32_t threads() const { return session_.hello().threads; }
  // The protocol version the session speaks, once authenticated.
  uint16_t version() const { return session_.version(); }
  // "name@address" once known, else the address: for logs.
  std::string Describe() const;
  // loop NowMs() of the last frame received.
  uint64_t last_heard_ms() const { return last_heard_ms_; }
  const protocol::HeartbeatMsg& last_heartbeat() const { return last_heartbeat_; }
  void set_last_heartbeat(const protocol::HeartbeatMsg& h) { last_heartbeat_ = h; }
  int64_t connected_unix_ms() const { return connected_unix_ms_; }
  size_t queued_bytes() const { return connection_->queued_bytes(); }

  // The master's bookkeeping (AgentConnections). Stale: the agent missed its heartbeats and its
  // leases were taken away; it gets no work until it speaks again (Revive).
  bool stale() const { return stale_; }
  void MarkStale() { stale_ = true; }
  // Heard from again: no longer stale. Returns whether it was.
  bool Revive() { return std::exchange(stale_, false); }
  // Declining: it handed leases back because it is stopping (Draining) or its machine is busy
  // (Overloaded); it gets no new work on this connection.
  bool declining() const { return declining_; }
  void Decline() { declining_ = true; }
  // Whether new leases may go to it: authenticated, not closing, not stale, not declining.
  bool TakesWork() const { return authenticated() && !closing_ && !stale_ && !declining_; }
  // Results accepted from this connection, of every job: kept here because a job's scheduler,
  // which accepts them, goes when the job stops running.
  uint64_t results_accepted() const { return results_accepted_; }
  void CountAccepted(uint64_t results) { results_accepted_ += results; }

 private:
  void OnFrame(std::span<const uint8_t> payload);
  void Fail(const std::string& reason);

  const Clock& clock_;
  std::unique_ptr<loop::FramedConnection> connection_;
  protocol::ProtocolSession session_;
  AgentLinkOptions options_;
  Callbacks callbacks_;
  loop::Timer handshake_deadline_;
  uint64_t id_;
  std::string address_;
  uint64_t last_heard_ms_ = 0;
  protocol::HeartbeatMsg last_heartbeat_;
  int64_t connected_unix_ms_ = 0;
  bool closing_ = false;
  bool was_authenticated_ = false;
  bool stale_ = false;
  bool declining_ = false;
  uint64_t results_accepted_ = 0;
};

}  // namespace radfarm::daemon
