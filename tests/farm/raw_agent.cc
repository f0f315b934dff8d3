#include "tests/farm/raw_agent.h"

#include <sys/socket.h>
#include <unistd.h>

#include <span>
#include <vector>

#include "protocol/protocol_session.h"
#include "tests/farm/raw_peer.h"

namespace radfarm::testing {
namespace {
constexpr std::chrono::seconds kHandshakeTimeout{60};  // generous: 2 shared cores
}  // namespace

struct RawAgent::Session {
  protocol::ProtocolSession session;
};

RawAgent::RawAgent(const std::string& host_port, const protocol::FarmSecret& secret,
                   const std::string& name)
    : fd_(ConnectTcpSocket(host_port)),
      session_(std::make_unique<Session>(
          Session{protocol::ProtocolSession::ForAgent(secret, {name, 1})})) {
  if (fd_ < 0) return;
  Result<std::vector<uint8_t>> hello = session_->session.Start();
  if (!hello ||
      !SendAll(std::string_view(reinterpret_cast<const char*>(hello->data()), hello->size()))) {
    return;
  }
  while (!session_->session.authenticated()) {
    const std::optional<std::string> payload = ReadFramePayload(fd_, kHandshakeTimeout);
    if (!payload) return;
    Result<protocol::DecodedFrame> frame = session_->session.Decode(
        std::span(reinterpret_cast<const uint8_t*>(payload->data()), payload->size()));
    if (!frame) return;
    Result<protocol::ProtocolSession::Accepted> accepted = session_->session.Accept(*frame);
    if (!accepted) return;
    const std::vector<uint8_t>& reply = accepted->reply;
    if (!reply.empty() &&
        !SendAll(std::string_view(reinterpret_cast<const char*>(reply.data()), reply.size()))) {
      return;
    }
  }
  welcomed_ = true;
}

RawAgent::~RawAgent() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<std::string> RawAgent::ReadClose(std::chrono::milliseconds timeout) {
  if (fd_ < 0) return std::nullopt;
  const std::optional<std::string> payload = ReadFramePayload(fd_, timeout);
  if (!payload) return std::nullopt;
  Result<protocol::DecodedFrame> frame = session_->session.Decode(
      std::span(reinterpret_cast<const uint8_t*>(payload->data()), payload->size()));
  if (!frame) return std::nullopt;
  const auto* close = std::get_if<protocol::CloseMsg>(&frame->message);
  if (close == nullptr) return std::nullopt;
  return close->detail;
}

bool RawAgent::SendAll(std::string_view bytes) {
  if (fd_ < 0) return false;
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n <= 0) return false;
    bytes.remove_prefix(size_t(n));
  }
  return true;
}

bool RawAgent::WaitForClose(std::chrono::milliseconds timeout) {
  return fd_ >= 0 && WaitForPeerClose(fd_, timeout);
}

}  // namespace radfarm::testing
