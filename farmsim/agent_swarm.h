// AgentSwarm: N simulated agents (SimAgent) on one event loop in one thread, all connected to one
// real radfarmd. Start() returns once every agent is authenticated; the swarm then works on
// whatever the master leases until the job ends, which the master announces by sending every
// agent a Cancel for it (JobRounds::DropRunner); Finish() waits for that and returns the agents'
// measurements.
//
// Threads: Start() and Finish() are called by one thread (the bench's); the agents, their timers
// and the event loop live on the swarm's own thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "farmsim/sim_agent.h"

namespace radfarm::sim {

struct SwarmConfig {
  std::string master_address;  // HOST:PORT, an IP literal
  std::string secret_hex;
  size_t agents = 10;
  SimAgentSettings agent;  // `master` is filled from master_address
  uint32_t heartbeat_ms = 1000;
  std::string name_prefix = "sim";
};

struct SwarmReport {
  std::vector<SimAgentStats> agents;
  // Every agent's rounds merged: earliest assignment, latest result, summed busy time.
  std::map<uint32_t, RoundSpan> rounds;
  double connect_seconds = 0;  // from the first connect to the last Welcome
  double job_start = -1;       // earliest first assignment (SteadySeconds)
  double job_end = -1;         // earliest Cancel arrival: the master finished the job
  double mean_lateness = 0;    // of the simulator's timers: its own measurement error
  double max_lateness = 0;
  double cpu_seconds = 0;           // the swarm thread's CPU time
  std::vector<std::string> errors;  // agents that closed before the end, with the reason
};

class AgentSwarm : private SwarmHooks {
 public:
  explicit AgentSwarm(SwarmConfig config);
  ~AgentSwarm() override;
  AgentSwarm(const AgentSwarm&) = delete;
  AgentSwarm& operator=(const AgentSwarm&) = delete;

  // Connects every agent; returns once all are authenticated. Throws std::runtime_error on an
  // error or after `timeout`.
  void Start(std::chrono::seconds timeout = std::chrono::seconds(60));
  // Waits for the job's end (the first Cancel), lets the other agents see it, closes every
  // connection and returns the measurements. Throws after `timeout`.
  SwarmReport Finish(std::chrono::seconds timeout);

 private:
  void Run();  // the swarm thread
  void OnAuthenticated() override;
  void OnCancel(uint64_t job_id, double arrival) override;
  void OnAgentClosed(const std::string& name, const std::string& reason) override;
  bool SceneVerified(const protocol::SceneHash& hash) const override;
  void OnSceneVerified(const protocol::SceneHash& hash) override;
  void BeginShutdown();

  SwarmConfig config_;
  loop::SocketAddress master_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::set<protocol::SceneHash> verified_scenes_;  // the swarm thread's
  // Shared with the bench thread under mutex_.
  size_t authenticated_ = 0;
  bool ended_ = false;     // the job ended (a Cancel arrived)
  bool finished_ = false;  // the swarm thread is done; report_ is final
  bool stop_ = false;      // the bench asks the swarm to stop (timeout)
  std::string failure_;
  SwarmReport report_;
};

}  // namespace radfarm::sim
