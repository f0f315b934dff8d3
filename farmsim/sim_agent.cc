#include "farmsim/sim_agent.h"

#include <variant>

#include "base/result.h"
#include "core/batch.h"
#include "farmsim/simulated_result.h"
#include "protocol/batch_convert.h"
#include "protocol/limits.h"

namespace radfarm::sim {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

constexpr uint32_t kMaxRequestsInFlight = 4;

}  // namespace

SimAgent::SimAgent(loop::EventLoop& loop, DelayLine& delays, const loop::SocketAddress& master,
                   const protocol::FarmSecret& secret, const SimAgentSettings& settings,
                   std::string name, SwarmHooks& hooks)
    : loop_(loop),
      delays_(delays),
      master_(master),
      settings_(settings),
      name_(std::move(name)),
      hooks_(hooks),
      // Version 5 at most: it traces no display points (PointLease), so the master traces a
      // finished job's display itself, as it does for any farm without version-6 agents.
      session_(protocol::ProtocolSession::ForAgent(
          secret, protocol::AgentConfig{name_, 1, protocol::kMinProtocolVersion,
                                        protocol::kPointLeaseVersion - 1})) {}

Status SimAgent::Connect() {
  loop::ConnectionOptions options;
  options.max_frame_bytes = protocol::kDefaultMaxFrameBytes;
  Result<std::unique_ptr<loop::FramedConnection>> connection = loop::FramedConnection::ConnectTcp(
      loop_, master_, options, [this](std::span<const uint8_t> payload) { OnFrame(payload); },
      [this](const std::string& reason) { hooks_.OnAgentClosed(name_, reason); },
      [this] {
        Result<std::vector<uint8_t>> hello = session_.Start();
        if (!hello) {
          Fail("cannot start the handshake: " + hello.error());
          return;
        }
        SendFrame(std::move(hello).value());
      });
  RADFARM_RETURN_IF_ERROR(connection);
  connection_ = std::move(connection).value();
  return Ok{};
}

void SimAgent::OnFrame(std::span<const uint8_t> payload) {
  const double now = SteadySeconds();
  stats_.bytes_received += payload.size() + 4;
  ++stats_.frames_received;
  std::vector<uint8_t> copy(payload.begin(), payload.end());
  if (settings_.latency_seconds <= 0) {
    Process(copy);
    return;
  }
  delays_.At(now + settings_.latency_seconds, [this, copy = std::move(copy)] { Process(copy); });
}

void SimAgent::Process(const std::vector<uint8_t>& payload) {
  if (session_.state() == protocol::ProtocolSession::State::kClosed || !open()) return;
  Result<protocol::DecodedFrame> frame = session_.Decode(payload);
  if (!frame) {
    Fail("bad frame from the master: " + frame.error());
    return;
  }
  const bool was_authenticated = session_.authenticated();
  Result<protocol::ProtocolSession::Accepted> accepted = session_.Accept(*frame);
  if (!accepted) {
    Fail(accepted.error());
    return;
  }
  if (!accepted->reply.empty()) SendFrame(std::move(accepted->reply));
  if (session_.peer_close()) {
    connection_->Close("the master closed: " + session_.peer_close()->detail);
    return;
  }
  if (!was_authenticated && session_.authenticated()) {
    SendHeartbeat();  // as a real agent does on its welcome (agent/agent.cc)
    hooks_.OnAuthenticated();
    return;
  }
  if (accepted->deliver) OnMessage(frame->message);
}

void SimAgent::OnMessage(const protocol::Message& message) {
  std::visit(Overloaded{
                 [&](const protocol::LeaseAssignmentMsg& m) { OnLease(m); },
                 [&](const protocol::LeaseRevokeMsg& m) { OnRevoke(m); },
                 [&](const protocol::SceneChunkMsg& m) { OnSceneChunk(m); },
                 [&](const protocol::CancelMsg& m) { OnCancel(m.job_id); },
                 [&](const protocol::SceneUnavailableMsg&) { Fail("the master lost a scene"); },
                 [&](const protocol::DrainMsg&) { Fail("the master drains its agents"); },
                 [&](const auto&) {},  // heartbeats: nothing to do
             },
             message);
}

void SimAgent::OnLease(const protocol::LeaseAssignmentMsg& lease) {
  const uint64_t group = next_group_++;
  groups_[group] = Group{lease.job_id, lease.batches.size(), {}, {}};
  for (size_t k = 0; k < lease.batches.size(); ++k)
    OnAssignment(protocol::BatchOf(lease, k), group);
}

void SimAgent::OnRevoke(const protocol::LeaseRevokeMsg& revoke) {
  std::set<std::tuple<uint64_t, uint64_t, uint32_t>> refs;
  for (const protocol::LeaseRef& l : revoke.leases)
    refs.insert({l.job_id, l.batch_id, l.attempt_id});
  std::vector<uint64_t> touched;
  const auto revoked = [&](const Queued& q) {
    const protocol::LeaseRef& l = q.batch.lease;
    if (refs.count({l.job_id, l.batch_id, l.attempt_id}) == 0) return false;
    touched.push_back(q.group);
    return true;
  };
  std::erase_if(queue_, revoked);
  std::erase_if(parked_, revoked);
  for (uint64_t group : touched) {
    const auto it = groups_.find(group);
    if (it == groups_.end()) continue;
    --it->second.outstanding;
    MaybeSendGroup(group);
  }
}

void SimAgent::MaybeSendGroup(uint64_t group) {
  const auto it = groups_.find(group);
  if (it == groups_.end() || it->second.outstanding > 0) return;
  if (!it->second.results.empty()) {
    Send(protocol::LeaseResultMsg{std::move(it->second.results)});
    stats_.last_result = SteadySeconds() + settings_.latency_seconds;
    for (uint32_t round : it->second.rounds) stats_.rounds[round].last_result = stats_.last_result;
  }
  groups_.erase(it);
}

void SimAgent::OnAssignment(const protocol::AssignedBatch& batch, uint64_t group) {
  const double now = SteadySeconds();
  const double at_socket = now - settings_.latency_seconds;
  if (stats_.first_assignment < 0) stats_.first_assignment = at_socket;
  RoundSpan& round = stats_.rounds[batch.round];
  if (round.first_assignment < 0) round.first_assignment = at_socket;
  Queued item{batch, now, group};
  if (scenes_.count(batch.scene_hash) > 0) {
    queue_.push_back(std::move(item));
    if (!computing_) StartNext();
    return;
  }
  parked_.push_back(std::move(item));
  auto [it, fresh] = fetching_.try_emplace(batch.scene_hash, batch.scene_hash);
  if (fresh) RequestSceneChunks(it->second);
}

void SimAgent::RequestSceneChunks(protocol::SceneAssembler& assembler) {
  for (uint32_t n = 0; n < kMaxRequestsInFlight; ++n) {
    std::optional<protocol::SceneRequestMsg> request = assembler.NextRequest();
    if (!request) return;
    Send(*request);
  }
}

void SimAgent::OnSceneChunk(const protocol::SceneChunkMsg& chunk) {
  stats_.scene_bytes_received += chunk.data.size();
  const auto it = fetching_.find(chunk.scene_hash);
  if (it == fetching_.end()) return;
  const bool last = chunk.offset + chunk.data.size() >= chunk.total_size;
  if (!last || !hooks_.SceneVerified(chunk.scene_hash)) {
    if (Status s = it->second.Add(chunk); !s) {
      Fail("scene fetch failed: " + s.error());
      return;
    }
    if (!it->second.complete()) {
      RequestSceneChunks(it->second);
      return;
    }
    // As a real agent's I/O queue does (once per scene in the swarm: SceneVerified).
    if (Result<std::vector<uint8_t>> unpacked = protocol::UnpackReceived(it->second.TakeReceived());
        !unpacked) {
      Fail("scene fetch failed: " + unpacked.error());
      return;
    }
    hooks_.OnSceneVerified(chunk.scene_hash);
  }
  scenes_.insert(chunk.scene_hash);
  fetching_.erase(it);
  for (auto p = parked_.begin(); p != parked_.end();) {
    if (p->batch.scene_hash != chunk.scene_hash) {
      ++p;
      continue;
    }
    p->arrival = SteadySeconds();
    queue_.push_back(std::move(*p));
    p = parked_.erase(p);
  }
  if (!computing_) StartNext();
}

void SimAgent::OnCancel(uint64_t job_id) {
  // Its arrival at the socket marks the job's end on the master's side.
  hooks_.OnCancel(job_id, SteadySeconds() - settings_.latency_seconds);
  const auto of_job = [job_id](const Queued& q) { return q.batch.lease.job_id == job_id; };
  std::erase_if(queue_, of_job);
  std::erase_if(parked_, of_job);
  std::erase_if(groups_, [job_id](const auto& g) { return g.second.job_id == job_id; });
  if (computing_ && of_job(current_)) {
    computing_ = false;
    ++generation_;  // its Finish is void
    busy_until_ = SteadySeconds();
    StartNext();
  }
}

void SimAgent::StartNext() {
  if (computing_ || queue_.empty()) return;
  current_ = std::move(queue_.front());
  queue_.pop_front();
  computing_ = true;
  const double start = std::max(current_.arrival, busy_until_);
  busy_until_ = start + double(current_.batch.ray_count) / settings_.rays_per_second;
  const uint64_t generation = generation_;
  delays_.At(busy_until_, [this, generation] { Finish(generation); });
}

void SimAgent::Finish(uint64_t generation) {
  if (generation != generation_ || !computing_) return;
  computing_ = false;
  const double seconds = double(current_.batch.ray_count) / settings_.rays_per_second;
  Result<protocol::BatchOutcome> result =
      MakeSimulatedResult(current_.batch, settings_.spread, seconds);
  if (!result) {
    Fail(result.error());
    return;
  }
  ++stats_.batches;
  stats_.rays += current_.batch.ray_count;
  stats_.busy_seconds += seconds;
  RoundSpan& round = stats_.rounds[current_.batch.round];
  round.busy_seconds += seconds;
  ++round.batches;
  if (current_.batch.round == kGatherRound) {
    stats_.ahead_compute.emplace_back(busy_until_ - seconds, busy_until_);
  }
  // The lease frame's results go out together once all its batches are done.
  if (const auto it = groups_.find(current_.group); it != groups_.end()) {
    it->second.results.push_back(std::move(*result));
    it->second.rounds.insert(current_.batch.round);
    --it->second.outstanding;
    MaybeSendGroup(current_.group);
  }
  StartNext();
}

void SimAgent::SendHeartbeat() {
  if (!authenticated()) return;
  protocol::HeartbeatMsg beat;
  beat.load = computing_ ? 1 : 0;
  beat.rays_per_second = settings_.rays_per_second;
  beat.leases_held = static_cast<uint32_t>(queue_.size() + parked_.size() + (computing_ ? 1 : 0));
  Send(beat);
}

void SimAgent::Shutdown() {
  if (!open()) return;
  if (session_.authenticated()) {
    Result<std::vector<uint8_t>> frame =
        session_.Encode(protocol::CloseMsg{protocol::CloseCode::kShutdown, "benchmark over"});
    if (frame) (void)connection_->SendPrefixed(std::move(frame).value());
  }
  connection_->CloseAfterFlush("benchmark over");
}

void SimAgent::Send(const protocol::Message& message) {
  Result<std::vector<uint8_t>> frame = session_.Encode(message);
  if (!frame) {
    Fail("cannot encode " + std::string(protocol::MessageName(message)) + ": " + frame.error());
    return;
  }
  SendFrame(std::move(frame).value());
}

void SimAgent::SendFrame(std::vector<uint8_t> frame) {
  const auto write = [this](std::vector<uint8_t> bytes) {
    if (!open()) return;
    stats_.bytes_sent += bytes.size();
    ++stats_.frames_sent;
    (void)connection_->SendPrefixed(std::move(bytes));
  };
  if (settings_.latency_seconds <= 0) {
    write(std::move(frame));
    return;
  }
  delays_.At(SteadySeconds() + settings_.latency_seconds,
             [write, frame = std::move(frame)]() mutable { write(std::move(frame)); });
}

void SimAgent::Fail(const std::string& reason) {
  if (!open()) return;
  (void)connection_->SendPrefixed(session_.CloseFrame());
  connection_->CloseAfterFlush(reason);
}

}  // namespace radfarm::sim
