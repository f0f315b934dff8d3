// MasterLink: one connection to the master. It connects over TCP, runs the agent's side of the
// handshake (ProtocolSession::ForAgent), and then passes checked messages both ways. It never
// reconnects: after on_closed the agent makes a new MasterLink.
//
//   connecting --TCP up: Hello sent--> handshaking --Welcome, master's tag ok: on_authenticated-->
//   authenticated --Close(), an error, the peer's Close or EOF, silence, failed connect--> closed
//
// Silence: until Welcome the whole handshake must finish within `handshake_timeout`; after it, a
// master that sends no byte for 4 heartbeat intervals is taken as gone. Any decode or session
// error is answered with the session's Close frame before the connection is dropped, as
// docs/PROTOCOL.md asks. A frame that fails authentication (protocol/frame_seal.h) is such an
// error: the agent reconnects as after any lost connection.
//
// Loop thread only. on_closed runs once, after the socket is closed; it may destroy the link.
// Destroying the link closes it silently.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "base/result.h"
#include "loop/event_loop.h"
#include "loop/framed_connection.h"
#include "loop/socket_address.h"
#include "protocol/farm_secret.h"
#include "protocol/protocol_session.h"

namespace radfarm::agent {

struct LinkClosed {
  std::string reason;
  bool auth_failed = false;  // either side refused the other's proof
  // The master closed with Close(Blocklisted): its results for a job failed validation too often.
  bool blocklisted = false;
  bool was_authenticated = false;
  // The master closed with Close right after its Welcome, before any other message: it refuses
  // this agent for now (it has its --max-agents, or this name has its connections); the detail
  // in `reason` says which.
  bool refused = false;
};

class MasterLink {
 public:
  struct Callbacks {
    std::function<void(const protocol::WelcomeMsg&)> on_authenticated;
    // Application messages (never the handshake, never Close: a Close ends in on_closed).
    std::function<void(const protocol::Message&)> on_message;
    std::function<void(const LinkClosed&)> on_closed;
  };
  struct Timing {
    std::chrono::milliseconds handshake_timeout{10000};
    std::chrono::milliseconds flush_timeout{500};  // Close(): how long the last frames may take
  };

  static Result<std::unique_ptr<MasterLink>> Connect(loop::EventLoop& loop,
                                                     const loop::SocketAddress& address,
                                                     const protocol::FarmSecret& secret,
                                                     const protocol::AgentConfig& config,
                                                     Timing timing, Callbacks callbacks);
  ~MasterLink();
  MasterLink(const MasterLink&) = delete;
  MasterLink& operator=(const MasterLink&) = delete;

  // Encodes and queues an application message. Fails when not authenticated, when the session
  // refuses it (e.g. a frame above the master's limit), or when the connection is closing.
  Status Send(const protocol::Message& message);
  // Sends Close{code, detail}, then closes once what is queued is written (or after
  // flush_timeout). on_closed follows.
  void Close(protocol::CloseCode code, const std::string& detail);
  // Writes what is queued (or gives up after flush_timeout), then closes the TCP connection
  // without a Close message, so the master takes it as a lost connection. on_closed follows.
  // The idle pause uses it. radfarmd requeues at once the leases of a connection that ends,
  // whether lost or closed with Close (AgentConnections::OnAgentClosed; agent/README.md, "Idle
  // policy").
  void Disconnect(const std::string& reason);

  bool authenticated() const { return session_.authenticated(); }
  uint16_t version() const { return session_.version(); }  // the negotiated protocol version
  const protocol::WelcomeMsg& welcome() const { return session_.welcome(); }
  const std::string& peer() const { return peer_; }

 private:
  MasterLink(const protocol::FarmSecret& secret, const protocol::AgentConfig& config,
             Callbacks callbacks);
  void OnConnected();
  void OnFrame(std::span<const uint8_t> payload);
  void OnClose(const std::string& reason);
  // A decode or session error: the session's Close frame, then drop the connection.
  void FailWith(const std::string& reason);

  protocol::ProtocolSession session_;
  Callbacks callbacks_;
  std::unique_ptr<loop::FramedConnection> connection_;
  std::string peer_;
  std::string close_reason_;  // set when we or the peer decided to close
  bool auth_failed_ = false;
  bool blocklisted_ = false;
  bool was_authenticated_ = false;
  bool heard_after_welcome_ = false;  // an application message came after the Welcome
  bool refused_ = false;
};

}  // namespace radfarm::agent
