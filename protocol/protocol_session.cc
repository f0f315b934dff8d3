#include "protocol/protocol_session.h"

#include <algorithm>
#include <utility>

#include "base/result.h"
#include "protocol/frame_codec.h"
#include "protocol/handshake_auth.h"
#include "protocol/message_checks.h"

namespace radfarm::protocol {
namespace {

bool IsHandshake(const Message& m) {
  return std::holds_alternative<HelloMsg>(m) || std::holds_alternative<ChallengeMsg>(m) ||
         std::holds_alternative<ProofMsg>(m) || std::holds_alternative<WelcomeMsg>(m);
}

bool MasterMaySend(const Message& m) {
  return std::holds_alternative<HeartbeatMsg>(m) || std::holds_alternative<CancelMsg>(m) ||
         std::holds_alternative<SceneChunkMsg>(m) ||
         std::holds_alternative<SceneUnavailableMsg>(m) || std::holds_alternative<DrainMsg>(m) ||
         std::holds_alternative<CloseMsg>(m) || std::holds_alternative<LeaseAssignmentMsg>(m) ||
         std::holds_alternative<LeaseRevokeMsg>(m) || std::holds_alternative<PointLeaseMsg>(m);
}

bool AgentMaySend(const Message& m) {
  return std::holds_alternative<HeartbeatMsg>(m) || std::holds_alternative<LeaseReturnMsg>(m) ||
         std::holds_alternative<SceneRequestMsg>(m) || std::holds_alternative<CloseMsg>(m) ||
         std::holds_alternative<LeaseResultMsg>(m) || std::holds_alternative<PointResultMsg>(m);
}

std::string VersionRange(uint16_t lo, uint16_t hi) {
  return std::to_string(lo) + ".." + std::to_string(hi);
}

// A reason as a Close detail: printable ASCII, cut to the limit.
std::string CloseDetail(std::string_view reason) {
  std::string detail(reason.substr(0, kMaxCloseDetailBytes));
  for (char& c : detail) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return detail;
}

}  // namespace

ProtocolSession::ProtocolSession(Role role, const FarmSecret& secret)
    : role_(role),
      secret_(secret),
      state_(role == Role::kMaster ? State::kAwaitingHello : State::kAwaitingChallenge) {}

ProtocolSession ProtocolSession::ForMaster(const FarmSecret& secret, const MasterConfig& config) {
  ProtocolSession session(Role::kMaster, secret);
  session.master_config_ = config;
  return session;
}

ProtocolSession ProtocolSession::ForAgent(const FarmSecret& secret, AgentConfig config) {
  ProtocolSession session(Role::kAgent, secret);
  session.agent_config_ = std::move(config);
  return session;
}

Result<std::vector<uint8_t>> ProtocolSession::Start() {
  if (role_ != Role::kAgent || state_ != State::kAwaitingChallenge || !hello_.agent_name.empty()) {
    return Error{"session: Start() is for a new agent session only"};
  }
  Result<Nonce> nonce = FreshNonce();
  if (!nonce) return Fail(CloseCode::kInternalError, nonce.error());
  hello_ = HelloMsg{agent_config_.min_version, agent_config_.max_version, agent_config_.name,
                    agent_config_.threads, *nonce};
  if (Status valid = CheckMessage(hello_); !valid) {
    return Fail(CloseCode::kInternalError, valid.error());
  }
  return EncodeFrame(hello_, hello_.max_version);
}

Result<DecodedFrame> ProtocolSession::Decode(std::span<const uint8_t> body) {
  if (state_ == State::kClosed) return Error{"session: frame after the session closed"};
  std::vector<uint8_t> opened;
  if (receive_seal_) {
    Result<std::vector<uint8_t>> plain = receive_seal_->Open(body);
    if (!plain) return Fail(CloseCode::kProtocolError, plain.error());
    opened = std::move(plain).value();
    body = opened;
  }
  Result<DecodedFrame> frame = DecodeFrameBody(body);
  if (!frame) return Fail(CloseCode::kProtocolError, frame.error());
  return frame;
}

Result<ProtocolSession::Accepted> ProtocolSession::Accept(const DecodedFrame& frame) {
  if (state_ == State::kClosed) return Error{"session: frame after the session closed"};
  if (const auto* close = std::get_if<CloseMsg>(&frame.message)) {
    peer_close_ = *close;
    state_ = State::kClosed;
    return Accepted{{}, true};
  }
  switch (state_) {
    case State::kAwaitingHello:
      return AcceptHello(frame);
    case State::kAwaitingChallenge:
      if (hello_.agent_name.empty()) {
        return Fail(CloseCode::kProtocolError, "session: frame before Start()");
      }
      return AcceptChallenge(frame);
    case State::kAwaitingProof:
      return AcceptProof(frame);
    case State::kAwaitingWelcome:
      return AcceptWelcome(frame);
    case State::kAuthenticated:
      return AcceptApplication(frame);
    case State::kClosed:
      break;
  }
  return Error{"session: frame after the session closed"};
}

Result<ProtocolSession::Accepted> ProtocolSession::AcceptHello(const DecodedFrame& frame) {
  const auto* hello = std::get_if<HelloMsg>(&frame.message);
  if (!hello) {
    return Fail(CloseCode::kProtocolError,
                "handshake: expected Hello, got " + std::string(MessageName(frame.message)));
  }
  if (frame.version != hello->max_version) {
    return Fail(CloseCode::kProtocolError, "handshake: Hello written in version " +
                                               std::to_string(frame.version) +
                                               ", not its max_version");
  }
  const uint16_t version = std::min(hello->max_version, kProtocolVersion);
  if (version < std::max(hello->min_version, kMinProtocolVersion)) {
    return Fail(CloseCode::kVersionMismatch,
                "handshake: no common protocol version: the agent speaks " +
                    VersionRange(hello->min_version, hello->max_version) + ", this master " +
                    VersionRange(kMinProtocolVersion, kProtocolVersion) +
                    "; install the same radfarm release on both");
  }
  if (master_config_.key_for_agent) {
    Result<ExpectedKey> expected = master_config_.key_for_agent(hello->agent_name);
    if (!expected) return Fail(CloseCode::kAuthFailed, "handshake: " + expected.error());
    secret_ = std::move(expected->key);
    secret_description_ = std::move(expected->description);
  }
  Result<Nonce> nonce = FreshNonce();
  if (!nonce) return Fail(CloseCode::kInternalError, nonce.error());
  hello_ = *hello;
  version_ = version;
  challenge_ = ChallengeMsg{version, *nonce};
  state_ = State::kAwaitingProof;
  return Accepted{EncodeFrame(challenge_, version_), false};
}

Result<ProtocolSession::Accepted> ProtocolSession::AcceptChallenge(const DecodedFrame& frame) {
  const auto* challenge = std::get_if<ChallengeMsg>(&frame.message);
  if (!challenge) {
    return Fail(CloseCode::kProtocolError,
                "handshake: expected Challenge, got " + std::string(MessageName(frame.message)));
  }
  if (challenge->version < hello_.min_version || challenge->version > hello_.max_version) {
    return Fail(CloseCode::kVersionMismatch,
                "handshake: master chose version " + std::to_string(challenge->version) +
                    ", agent speaks " + VersionRange(hello_.min_version, hello_.max_version));
  }
  if (frame.version != challenge->version) {
    return Fail(CloseCode::kProtocolError, "handshake: Challenge written in version " +
                                               std::to_string(frame.version) +
                                               ", not the version it chose");
  }
  challenge_ = *challenge;
  version_ = challenge->version;
  state_ = State::kAwaitingWelcome;
  return Accepted{EncodeFrame(ProofMsg{AgentTag(secret_, hello_, challenge_)}, version_), false};
}

Result<ProtocolSession::Accepted> ProtocolSession::AcceptProof(const DecodedFrame& frame) {
  const auto* proof = std::get_if<ProofMsg>(&frame.message);
  if (!proof) {
    return Fail(CloseCode::kProtocolError,
                "handshake: expected Proof, got " + std::string(MessageName(frame.message)));
  }
  if (frame.version != version_) {
    return Fail(CloseCode::kProtocolError, "handshake: Proof written in version " +
                                               std::to_string(frame.version) + ", not " +
                                               std::to_string(version_));
  }
  if (!TagsEqual(proof->tag, AgentTag(secret_, hello_, challenge_))) {
    return Fail(CloseCode::kAuthFailed,
                "handshake: the agent's proof does not match " + secret_description_);
  }
  welcome_ = WelcomeMsg{MasterTag(secret_, hello_, challenge_), master_config_.agent_id,
                        master_config_.heartbeat_interval_ms, master_config_.max_frame_bytes};
  if (Status valid = CheckMessage(welcome_); !valid) {
    return Fail(CloseCode::kInternalError, valid.error());
  }
  state_ = State::kAuthenticated;
  std::vector<uint8_t> welcome_frame = EncodeFrame(welcome_, version_);
  StartSealing();  // after the Welcome, which the agent must read in clear
  return Accepted{std::move(welcome_frame), false};
}

Result<ProtocolSession::Accepted> ProtocolSession::AcceptWelcome(const DecodedFrame& frame) {
  // The master seals everything after its Welcome, so we seal our answer even when it is a
  // Close refusing that Welcome: a genuine master whose Welcome was tampered with on the way
  // then reads why, and a master without the secret reads nothing.
  StartSealing();
  const auto* welcome = std::get_if<WelcomeMsg>(&frame.message);
  if (!welcome) {
    return Fail(CloseCode::kProtocolError,
                "handshake: expected Welcome, got " + std::string(MessageName(frame.message)));
  }
  if (frame.version != version_) {
    return Fail(CloseCode::kProtocolError, "handshake: Welcome written in version " +
                                               std::to_string(frame.version) + ", not " +
                                               std::to_string(version_));
  }
  if (!TagsEqual(welcome->tag, MasterTag(secret_, hello_, challenge_))) {
    return Fail(CloseCode::kAuthFailed,
                "handshake: the master's proof does not match the farm secret");
  }
  welcome_ = *welcome;
  state_ = State::kAuthenticated;
  return Accepted{{}, false};
}

Result<ProtocolSession::Accepted> ProtocolSession::AcceptApplication(const DecodedFrame& frame) {
  if (IsHandshake(frame.message)) {
    return Fail(CloseCode::kProtocolError,
                "session: " + std::string(MessageName(frame.message)) + " after authentication");
  }
  if (!PeerMaySend(frame.message)) {
    return Fail(CloseCode::kProtocolError,
                "session: " + std::string(MessageName(frame.message)) + " may not be sent by " +
                    (role_ == Role::kMaster ? "an agent" : "the master"));
  }
  if (frame.version != version_) {
    return Fail(CloseCode::kProtocolError, "session: frame written in version " +
                                               std::to_string(frame.version) + ", not " +
                                               std::to_string(version_));
  }
  if (!InVersion(frame.message, version_)) {
    return Fail(CloseCode::kProtocolError, "session: " + std::string(MessageName(frame.message)) +
                                               " is not a message of protocol version " +
                                               std::to_string(version_));
  }
  return Accepted{{}, true};
}

Result<std::vector<uint8_t>> ProtocolSession::Encode(const Message& message) {
  const std::string name(MessageName(message));
  if (state_ == State::kClosed) return Error{"session: cannot send " + name + ": closed"};
  if (IsHandshake(message)) {
    return Error{"session: " + name + " is sent by the session itself"};
  }
  const bool is_close = std::holds_alternative<CloseMsg>(message);
  if (!is_close && state_ != State::kAuthenticated) {
    return Error{"session: cannot send " + name + " before authentication"};
  }
  if (!(role_ == Role::kMaster ? MasterMaySend(message) : AgentMaySend(message))) {
    return Error{"session: " + name + " may not be sent by " +
                 (role_ == Role::kMaster ? "the master" : "an agent")};
  }
  if (!InVersion(message, WireVersion())) {
    return Error{"session: " + name + " is not a message of protocol version " +
                 std::to_string(WireVersion())};
  }
  RADFARM_RETURN_IF_ERROR(CheckMessage(message));
  std::vector<uint8_t> frame = EncodeFrame(message, WireVersion());
  if (send_seal_) frame = send_seal_->Seal(frame);
  if (role_ == Role::kAgent && state_ == State::kAuthenticated &&
      frame.size() - kLengthPrefixBytes > welcome_.max_frame_bytes) {
    return Error{"session: " + name + " frame of " + std::to_string(frame.size()) +
                 " bytes exceeds the master's limit of " +
                 std::to_string(welcome_.max_frame_bytes) + " (use smaller batches)"};
  }
  if (is_close) state_ = State::kClosed;
  return frame;
}

void ProtocolSession::Abort(std::string_view reason) {
  if (state_ != State::kClosed || failure_reason_.empty()) {
    failure_code_ = CloseCode::kProtocolError;
    failure_reason_ = std::string(reason);
  }
  state_ = State::kClosed;
}

std::vector<uint8_t> ProtocolSession::CloseFrame() {
  std::vector<uint8_t> frame =
      EncodeFrame(CloseMsg{failure_code_, CloseDetail(failure_reason_)}, WireVersion());
  return send_seal_ ? send_seal_->Seal(frame) : frame;
}

void ProtocolSession::StartSealing() {
  const SessionKeys keys = DeriveSessionKeys(secret_, hello_, challenge_);
  const SealMode mode = SealModeFromEnvironment();
  const bool master = role_ == Role::kMaster;
  send_seal_.emplace(master ? keys.master_to_agent : keys.agent_to_master, mode);
  receive_seal_.emplace(master ? keys.agent_to_master : keys.master_to_agent, mode);
}

uint16_t ProtocolSession::WireVersion() const {
  if (version_ != 0) return version_;
  // Before the Challenge: an agent writes in the version its Hello was written in.
  if (role_ == Role::kAgent && hello_.max_version != 0) return hello_.max_version;
  return kProtocolVersion;
}

Error ProtocolSession::Fail(CloseCode code, std::string reason) {
  failure_code_ = code;
  failure_reason_ = reason;
  state_ = State::kClosed;
  return Error{std::move(reason)};
}

bool ProtocolSession::PeerMaySend(const Message& message) const {
  return role_ == Role::kMaster ? AgentMaySend(message) : MasterMaySend(message);
}

std::string_view SessionStateName(ProtocolSession::State state) {
  using S = ProtocolSession::State;
  switch (state) {
    case S::kAwaitingHello:
      return "awaiting Hello";
    case S::kAwaitingChallenge:
      return "awaiting Challenge";
    case S::kAwaitingProof:
      return "awaiting Proof";
    case S::kAwaitingWelcome:
      return "awaiting Welcome";
    case S::kAuthenticated:
      return "authenticated";
    case S::kClosed:
      return "closed";
  }
  return "unknown";
}

}  // namespace radfarm::protocol
