// The master's job, agent and event objects (docs/CONTROL.md, "Objects"), read strictly from its
// JSON: every documented key must be present with its documented type, or the read fails naming
// the key. Keys the CLI does not know are ignored, so a newer master still works.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"
#include "core/job_timeline.h"

namespace radfarm {

struct JobInfo {
  int64_t id = 0;
  std::string name;
  std::string state;  // queued, running, paused, held, done, failed, cancelled
  int64_t priority = 0;
  uint64_t seed = 0;
  std::string scene_hash;
  uint64_t patches = 0;
  std::optional<int64_t> submitted_at_ms, started_at_ms, finished_at_ms;
  std::optional<std::string> error;
  uint64_t round = 0;
  uint64_t rays = 0;
  double unshot_fraction = 1;
  double tolerance = 0;
  double progress = 0;
  double rays_per_second = 0;
  uint64_t agents = 0;
  std::optional<double> eta_seconds;
  std::optional<std::string> stop_reason;
  bool waiting_for_agents = false;  // its round is leased out and no agent is connected
  // Of a job the master runs: preparing, round, reducing, finishing or display (its display being
  // drawn after its rounds); none otherwise.
  std::optional<std::string> phase;
  // The rules the job's scene got at its size (core/solve_rules.h); null before it is prepared.
  std::optional<std::string> direct_start;
  std::optional<std::string> display;
  // Where its time went on the master and its agents (core/job_timeline.h); empty when unknown.
  JobTimeline timeline;
};

struct AgentInfo {
  int64_t id = 0;
  std::string name;
  std::string address;
  uint64_t threads = 0;
  double rays_per_second = 0;
  double load = 0;
  uint64_t leases = 0;
  int64_t connected_ms = 0;
  int64_t last_heartbeat_ms_ago = 0;
  uint64_t results = 0;
};

struct EventInfo {
  int64_t time_ms = 0;
  std::string level;  // info, warning, error
  std::string text;
  std::optional<int64_t> job{};  // the job it is about; none for the farm's own
};

// done, failed and cancelled: the job will not change again.
bool IsTerminalState(std::string_view state);

// `where` names the object in errors ("job", "jobs[2]").
Result<JobInfo> ParseJob(const nlohmann::json& object, const std::string& where);
Result<AgentInfo> ParseAgent(const nlohmann::json& object, const std::string& where);
Result<EventInfo> ParseEvent(const nlohmann::json& object, const std::string& where);

}  // namespace radfarm
