// ProtocolSession: the protocol state of one connection, on the master's or the agent's end. It
// runs the mutual HMAC handshake itself and, once both sides are authenticated, lets through only
// the messages that may travel in its direction. It does no I/O: the caller decodes frames
// (FrameDecoder), hands them to Accept(), writes the replies it returns, and acts on the messages
// it delivers.
//
// States (docs/PROTOCOL.md, "Handshake"):
//
//   master:  AwaitingHello --Hello / reply Challenge--> AwaitingProof
//                          --Proof, agent tag ok / reply Welcome--> Authenticated
//   agent:   Start() sends Hello --> AwaitingChallenge --Challenge / reply Proof--> AwaitingWelcome
//                          --Welcome, master tag ok--> Authenticated
//   any state --Close received or sent, Abort(), or any protocol error--> Closed
//
// Before Authenticated nothing but the next handshake message (or a Close) is accepted; a
// repeated, replayed or out-of-order handshake message is an error, and so is a frame written in
// another version than the negotiated one. Closed is final: every later frame is an error.
//
// Every frame after the Welcome is sealed (frame_seal.h) with keys derived from the handshake:
// Decode() opens what arrives, Encode() and CloseFrame() seal what goes out. A frame that fails to
// open closes the session ("frame failed authentication").
//
// Master:                                           Agent:
//   Result<DecodedFrame> f = session.Decode(body);    Write(*session.Start());
//   Result<Accepted> a = f ? session.Accept(*f) : f.error();   ... then the same loop.
//   if (!a) { Log(a.error());
//             Write(session.CloseFrame()); Drop(); }
//   Write(a->reply);                // may be empty
//   if (a->deliver) Handle(frame.message);
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "protocol/agent_key.h"
#include "protocol/farm_secret.h"
#include "protocol/frame_seal.h"
#include "protocol/messages.h"

namespace radfarm::protocol {

struct MasterConfig {
  uint64_t agent_id = 0;  // told to the agent in Welcome, for logs on both sides
  uint32_t heartbeat_interval_ms = 5000;
  uint32_t max_frame_bytes = kDefaultMaxFrameBytes;  // the master's FrameDecoder limit
  // Per-agent credentials (agent_key.h): given the Hello's agent name, the key that agent must
  // prove itself with, in place of the session's secret for the proofs and the frame keys; an
  // error (a revoked name) refuses it with Close(AuthFailed). Unset: the farm secret for all.
  std::function<Result<ExpectedKey>(const std::string& agent_name)> key_for_agent;
};

struct AgentConfig {
  std::string name;  // IsValidAgentName
  uint32_t threads = 1;
  uint16_t min_version = kMinProtocolVersion;
  uint16_t max_version = kProtocolVersion;
};

class ProtocolSession {
 public:
  enum class Role { kMaster, kAgent };
  enum class State {
    kAwaitingHello,      // master: connection accepted
    kAwaitingChallenge,  // agent: Hello sent
    kAwaitingProof,      // master: Challenge sent
    kAwaitingWelcome,    // agent: Proof sent
    kAuthenticated,
    kClosed,
  };

  // What Accept() wants done with an accepted frame.
  struct Accepted {
    std::vector<uint8_t> reply;  // a handshake frame to write now; empty if none
    bool deliver = false;        // an application message (or a Close): the caller acts on it
  };

  static ProtocolSession ForMaster(const FarmSecret& secret, const MasterConfig& config);
  static ProtocolSession ForAgent(const FarmSecret& secret, AgentConfig config);

  // Agent only, once, first: the Hello frame that opens the connection.
  Result<std::vector<uint8_t>> Start();

  // Opens (once authenticated) and decodes the bytes after one frame's length prefix
  // (DecodeFrameBody). An error closes the session like Accept's.
  Result<DecodedFrame> Decode(std::span<const uint8_t> body);

  // Runs one incoming, already verified frame through the state machine. An error moves the
  // session to Closed; CloseFrame() then says why, for the peer.
  Result<Accepted> Accept(const DecodedFrame& frame);

  // Encodes an outgoing application message (not a handshake message: the session sends those),
  // after checking its values and that this side may send it now. Sending a Close closes.
  Result<std::vector<uint8_t>> Encode(const Message& message);

  // Closes after an error found outside the session (e.g. by the FrameDecoder).
  void Abort(std::string_view reason);
  // The Close frame to write before dropping the connection: the failure code and reason after
  // an error or Abort(), else a normal close. Sealed once authenticated (it uses up a counter).
  std::vector<uint8_t> CloseFrame();
  // The code CloseFrame() carries.
  CloseCode failure_code() const { return failure_code_; }

  Role role() const { return role_; }
  State state() const { return state_; }
  bool authenticated() const { return state_ == State::kAuthenticated; }
  // The negotiated version; 0 until the Challenge.
  uint16_t version() const { return version_; }
  // The agent's Hello (name, threads), on both ends once it has been sent or received.
  const HelloMsg& hello() const { return hello_; }
  // The master's Welcome (agent id, heartbeat interval, frame limit), on the agent once
  // authenticated.
  const WelcomeMsg& welcome() const { return welcome_; }
  // Set once a Close has been received.
  const std::optional<CloseMsg>& peer_close() const { return peer_close_; }

 private:
  ProtocolSession(Role role, const FarmSecret& secret);

  Result<Accepted> AcceptHello(const DecodedFrame& frame);
  Result<Accepted> AcceptChallenge(const DecodedFrame& frame);
  Result<Accepted> AcceptProof(const DecodedFrame& frame);
  Result<Accepted> AcceptWelcome(const DecodedFrame& frame);
  Result<Accepted> AcceptApplication(const DecodedFrame& frame);
  Error Fail(CloseCode code, std::string reason);
  // The version outgoing frames are written in: the negotiated one once there is one.
  uint16_t WireVersion() const;
  // Whether the peer (the other role) may send `message` once authenticated.
  bool PeerMaySend(const Message& message) const;
  // Derives the session keys; from now on frames both ways are sealed.
  void StartSealing();

  Role role_;
  FarmSecret secret_;
  std::string secret_description_ = "the farm secret";  // for the proof's failure message
  State state_;
  MasterConfig master_config_;
  AgentConfig agent_config_;
  uint16_t version_ = 0;
  HelloMsg hello_;
  ChallengeMsg challenge_;
  WelcomeMsg welcome_;
  std::optional<CloseMsg> peer_close_;
  std::optional<FrameSeal> send_seal_;
  std::optional<FrameSeal> receive_seal_;
  CloseCode failure_code_ = CloseCode::kNormal;
  std::string failure_reason_;
};

std::string_view SessionStateName(ProtocolSession::State state);

}  // namespace radfarm::protocol
