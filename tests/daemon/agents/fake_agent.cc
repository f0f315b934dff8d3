#include "tests/daemon/agents/fake_agent.h"

#include <utility>
#include <variant>

#include "farmsim/simulated_result.h"
#include "protocol/batch_convert.h"

namespace radfarm::daemon::fakes {

FakeAgent::FakeAgent(loop::EventLoop& loop, const loop::SocketAddress& master,
                     const protocol::FarmSecret& secret, std::string name, bool answering)
    : loop_(loop),
      master_(master),
      name_(std::move(name)),
      answering_(answering),
      session_(protocol::ProtocolSession::ForAgent(secret, protocol::AgentConfig{name_, 1})) {}

FakeAgent::~FakeAgent() { Drop(); }

Status FakeAgent::Connect() {
  loop::ConnectionOptions options;
  auto connection = loop::FramedConnection::ConnectTcp(
      loop_, master_, options, [this](std::span<const uint8_t> payload) { OnFrame(payload); },
      [this](const std::string& reason) {
        if (!closed_reason_) closed_reason_ = reason;
      },
      [this] {
        Result<std::vector<uint8_t>> hello = session_.Start();
        if (!hello) return Fail("cannot start the handshake: " + hello.error());
        (void)connection_->SendPrefixed(std::move(hello).value());
      });
  RADFARM_RETURN_IF_ERROR(connection);
  connection_ = std::move(connection).value();
  return Ok{};
}

void FakeAgent::Drop() {
  if (connection_ && connection_->state() == loop::HandleState::kOpen) {
    connection_->Close("dropped by the test");
  }
}

void FakeAgent::SendHeartbeat() {
  Send(protocol::HeartbeatMsg{0, 1e6, static_cast<uint32_t>(held_.size())});
}

void FakeAgent::OnFrame(std::span<const uint8_t> payload) {
  Result<protocol::DecodedFrame> frame = session_.Decode(payload);
  if (!frame) return Fail("bad frame from the master: " + frame.error());
  const bool was_authenticated = session_.authenticated();
  Result<protocol::ProtocolSession::Accepted> accepted = session_.Accept(*frame);
  if (!accepted) return Fail(accepted.error());
  if (!accepted->reply.empty()) (void)connection_->SendPrefixed(std::move(accepted->reply));
  if (session_.peer_close()) {
    closed_reason_ = session_.peer_close()->detail;
    connection_->Close("the master closed");
    return;
  }
  if (!was_authenticated && session_.authenticated()) {
    SendHeartbeat();  // as radfarm-agent on its welcome
    return;
  }
  if (!accepted->deliver) return;
  if (const auto* lease = std::get_if<protocol::LeaseAssignmentMsg>(&frame->message)) {
    OnLease(*lease);
  } else if (const auto* piece = std::get_if<protocol::PointLeaseMsg>(&frame->message)) {
    OnPointLease(*piece);
  } else if (const auto* cancel = std::get_if<protocol::CancelMsg>(&frame->message)) {
    cancelled_jobs_.push_back(cancel->job_id);
    std::erase_if(held_, [&](const BatchKey& key) { return std::get<0>(key) == cancel->job_id; });
    std::erase_if(pieces_held_, [&](const auto& key) { return key.first == cancel->job_id; });
    std::erase_if(start_pieces_held_, [&](const auto& key) { return key.first == cancel->job_id; });
  }
}

void FakeAgent::OnPointLease(const protocol::PointLeaseMsg& lease) {
  if (lease.start_sections > 0) {
    // A start's patches: a grey direct light on every one (no punctual light in the test scenes).
    ++start_pieces_received_;
    if (!answering_starts_) {
      start_pieces_held_.insert({lease.lease.job_id, lease.lease.batch_id});
      return;
    }
    protocol::PointResultMsg answer;
    answer.lease = lease.lease;
    answer.direct.assign(lease.start_patches, Rgb{0.25, 0.25, 0.25});
    answer.rays = lease.start_patches;
    ++results_sent_;
    Send(answer);
    return;
  }
  ++pieces_received_;
  if (!answering_pieces_.value_or(answering_)) {
    pieces_held_.insert({lease.lease.job_id, lease.lease.batch_id});
    return;
  }
  const size_t n = lease.points.size();
  protocol::PointResultMsg answer;
  answer.lease = lease.lease;
  if (lease.near_radius > 0) answer.near.assign(n, 0);
  if (lease.direct) answer.direct.assign(n, Rgb());
  if (!lease.gather.empty()) answer.gathered.assign(n, Rgb());
  answer.rays = n;
  ++results_sent_;
  Send(answer);
}

void FakeAgent::OnLease(const protocol::LeaseAssignmentMsg& lease) {
  protocol::LeaseResultMsg answer;
  for (size_t k = 0; k < lease.batches.size(); ++k) {
    const BatchKey key{lease.job_id, lease.round, lease.batches[k].batch_id};
    leased_.insert(key);
    ++batches_received_;
    if (!answering_) {
      held_.insert(key);
      continue;
    }
    Result<protocol::BatchOutcome> result =
        sim::MakeSimulatedResult(protocol::BatchOf(lease, k), 4, 0.001);
    if (!result) return Fail("cannot simulate a result: " + result.error());
    answer.results.push_back(std::move(result).value());
  }
  if (answer.results.empty()) return;
  results_sent_ += answer.results.size();
  Send(answer);
}

void FakeAgent::Send(const protocol::Message& message) {
  Result<std::vector<uint8_t>> frame = session_.Encode(message);
  if (!frame) return Fail("cannot encode: " + frame.error());
  (void)connection_->SendPrefixed(std::move(frame).value());
}

void FakeAgent::Fail(const std::string& reason) {
  if (!closed_reason_) closed_reason_ = reason;
  if (connection_ && connection_->state() == loop::HandleState::kOpen) {
    connection_->Close(reason);
  }
}

}  // namespace radfarm::daemon::fakes
