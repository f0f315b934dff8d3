// SimAgent: one simulated farm agent. It speaks the real protocol to a real radfarmd over a real
// TCP connection (loop::FramedConnection::ConnectTcp, protocol::ProtocolSession::ForAgent: the
// HMAC handshake, heartbeats, scene fetch by hash), but computes nothing: each BatchAssignment
// takes ray_count / rays_per_second seconds of simulated time, one batch after another (a
// one-thread "office machine"), and a LeaseAssignment's batches are answered together in one
// LeaseResult of MakeSimulatedResults; a LeaseRevoke drops the named batches still queued. An
// optional one-way latency delays every frame it sends and every frame it receives. It speaks
// protocol version 5, so it is never leased a display's points. Its
// heartbeats (the first right after the welcome, as a real agent's) report its speed from the
// start: an agent that has worked before, whose meter holds its recent batches.
//
// Time: busy periods chain exactly in simulated time: a batch starts when the previous one's
// compute ends or when it arrives, whichever is later, however late the DelayLine runs the
// completion; only the result's send time carries the simulator's lateness.
//
// Loop thread only. The agent reports to its SwarmHooks (the AgentSwarm) and never destroys
// itself.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "farmsim/delay_line.h"
#include "loop/framed_connection.h"
#include "protocol/farm_secret.h"
#include "protocol/protocol_session.h"
#include "protocol/scene_transfer.h"

namespace radfarm::sim {

struct SimAgentSettings {
  double rays_per_second = 1e6;  // simulated compute speed
  double latency_seconds = 0;    // added to every frame, each way
  uint32_t spread = 4;           // patches a result's rays are spread over
};

// One round as one agent saw it. Times are SteadySeconds() at the sockets (the added latency
// taken out); -1 when it never happened.
struct RoundSpan {
  double first_assignment = -1;  // the round's first lease arrived
  double last_result = -1;       // its last result reached the master
  double busy_seconds = 0;       // simulated compute of its results
  uint64_t batches = 0;
};

// What an agent measured. Times are SteadySeconds(); -1 when it never happened.
struct SimAgentStats {
  uint64_t bytes_sent = 0, bytes_received = 0;  // frames with their 4-byte prefixes
  uint64_t frames_sent = 0, frames_received = 0;
  uint64_t scene_bytes_received = 0;     // of bytes_received: SceneChunk frames
  uint64_t batches = 0, rays = 0;        // results sent
  double busy_seconds = 0;               // simulated compute of the results sent
  double first_assignment = -1;          // arrival on the socket (before the added latency)
  double last_result = -1;               // when the last result went to the socket
  std::map<uint32_t, RoundSpan> rounds;  // by round number
  // When it computed the final gather's batches leased ahead of their round (round kGatherRound,
  // daemon/jobs/gather_ahead.h), (start, end): they run across the other rounds, and the report
  // tells the time within those from the time between them.
  std::vector<std::pair<double, double>> ahead_compute;
};

class SwarmHooks {
 public:
  virtual ~SwarmHooks() = default;
  virtual void OnAuthenticated() = 0;
  // A Cancel arrived on the socket at `arrival` (before the added latency).
  virtual void OnCancel(uint64_t job_id, double arrival) = 0;
  virtual void OnAgentClosed(const std::string& name, const std::string& reason) = 0;
  // Scenes an agent of the swarm has decompressed and hashed. The others receive every byte of
  // such a scene but skip that last step: 1000 real agents take it at once, each on its own
  // machine, and taken one after another here it held the last of 1000 back by about 0.4 s.
  virtual bool SceneVerified(const protocol::SceneHash& hash) const = 0;
  virtual void OnSceneVerified(const protocol::SceneHash& hash) = 0;
};

class SimAgent {
 public:
  SimAgent(loop::EventLoop& loop, DelayLine& delays, const loop::SocketAddress& master,
           const protocol::FarmSecret& secret, const SimAgentSettings& settings, std::string name,
           SwarmHooks& hooks);
  SimAgent(const SimAgent&) = delete;
  SimAgent& operator=(const SimAgent&) = delete;

  Status Connect();
  void SendHeartbeat();
  // Close(Shutdown), then the TCP close once it is written.
  void Shutdown();

  bool open() const { return connection_ && connection_->state() == loop::HandleState::kOpen; }
  bool authenticated() const { return session_.authenticated(); }
  const SimAgentStats& stats() const { return stats_; }
  const std::string& name() const { return name_; }

 private:
  struct Queued {
    protocol::AssignedBatch batch;
    double arrival;  // after the added latency: when the agent could start it
    uint64_t group = 0;
  };
  // One LeaseAssignment's batches, answered together.
  struct Group {
    uint64_t job_id = 0;
    size_t outstanding = 0;  // batches neither computed nor revoked
    std::vector<protocol::BatchOutcome> results;
    std::set<uint32_t> rounds;
  };

  void OnFrame(std::span<const uint8_t> payload);
  void Process(const std::vector<uint8_t>& payload);
  void OnMessage(const protocol::Message& message);
  void OnLease(const protocol::LeaseAssignmentMsg& lease);
  void OnRevoke(const protocol::LeaseRevokeMsg& revoke);
  void OnAssignment(const protocol::AssignedBatch& batch, uint64_t group);
  void MaybeSendGroup(uint64_t group);
  void OnSceneChunk(const protocol::SceneChunkMsg& chunk);
  void OnCancel(uint64_t job_id);
  void RequestSceneChunks(protocol::SceneAssembler& assembler);
  void StartNext();
  void Finish(uint64_t generation);
  // Writes an encoded frame (prefix included) after the added latency.
  void SendFrame(std::vector<uint8_t> frame);
  void Send(const protocol::Message& message);
  void Fail(const std::string& reason);

  loop::EventLoop& loop_;
  DelayLine& delays_;
  loop::SocketAddress master_;
  SimAgentSettings settings_;
  std::string name_;
  SwarmHooks& hooks_;
  protocol::ProtocolSession session_;
  std::unique_ptr<loop::FramedConnection> connection_;
  SimAgentStats stats_;

  std::set<protocol::SceneHash> scenes_;  // fetched
  std::map<protocol::SceneHash, protocol::SceneAssembler> fetching_;
  std::deque<Queued> parked_;  // waiting for their scene
  std::deque<Queued> queue_;   // waiting for the compute "thread"
  bool computing_ = false;
  Queued current_{};
  double busy_until_ = 0;    // simulated end of the current or last batch
  uint64_t generation_ = 0;  // bumped by Cancel: a pending Finish of a cancelled batch is void
  std::map<uint64_t, Group> groups_;
  uint64_t next_group_ = 1;
};

}  // namespace radfarm::sim
