#include "tests/cli/control_fixtures.h"

#include <cmath>

namespace radfarm::testing {

const std::vector<std::string> kJobKeys = {"id",
                                           "name",
                                           "state",
                                           "priority",
                                           "seed",
                                           "scene_hash",
                                           "patches",
                                           "submitted_at_ms",
                                           "started_at_ms",
                                           "finished_at_ms",
                                           "error",
                                           "round",
                                           "rays",
                                           "unshot_fraction",
                                           "tolerance",
                                           "progress",
                                           "rays_per_second",
                                           "agents",
                                           "eta_seconds",
                                           "stop_reason",
                                           "waiting_for_agents",
                                           "phase",
                                           "last_checkpoint",
                                           "direct_start",
                                           "display"};
const std::vector<std::string> kAgentKeys = {"id",
                                             "name",
                                             "address",
                                             "threads",
                                             "rays_per_second",
                                             "load",
                                             "leases",
                                             "connected_ms",
                                             "last_heartbeat_ms_ago",
                                             "results"};
const std::vector<std::string> kEventKeys = {"time_ms", "level", "job", "text"};

nlohmann::json JobObject(int64_t id, const std::string& state, uint64_t round) {
  const bool ended = state == "done" || state == "failed" || state == "cancelled";
  const bool started = round > 0 || state == "running" || ended;
  const double unshot = std::pow(0.5, double(round));
  return {{"id", id},
          {"name", "job-" + std::to_string(id)},
          {"state", state},
          {"priority", 5},
          {"seed", 17},
          {"scene_hash", std::string(64, 'a')},
          {"patches", 2688},
          {"submitted_at_ms", 1795000000000},
          {"started_at_ms", started ? nlohmann::json(1795000001000) : nlohmann::json()},
          {"finished_at_ms", ended ? nlohmann::json(1795000061000) : nlohmann::json()},
          {"error", state == "failed" ? nlohmann::json("agent lost the scene") : nlohmann::json()},
          {"round", round},
          {"rays", round * 1000000},
          {"unshot_fraction", unshot},
          {"tolerance", 0.001},
          {"progress", round == 0 ? 0.0 : std::log(unshot) / std::log(0.001)},
          {"rays_per_second", state == "running" ? 2.5e6 : 0.0},
          {"agents", state == "running" ? 2 : 0},
          {"eta_seconds", state == "running" ? nlohmann::json(42.0) : nlohmann::json()},
          {"stop_reason", state == "done" ? nlohmann::json("converged") : nlohmann::json()},
          {"waiting_for_agents", false},
          {"phase", state == "running" ? nlohmann::json("round") : nlohmann::json()},
          {"last_checkpoint", nlohmann::json()},
          {"direct_start", nlohmann::json()},
          {"display", nlohmann::json()}};
}

nlohmann::json AgentObject(int64_t id, const std::string& name) {
  return {{"id", id},
          {"name", name},
          {"address", "10.0.0." + std::to_string(id) + ":7070"},
          {"threads", 16},
          {"rays_per_second", 8.25e6},
          {"load", 0.75},
          {"leases", 3},
          {"connected_ms", 1795000000000},
          {"last_heartbeat_ms_ago", 1200},
          {"results", 99}};
}

nlohmann::json EventObject(int64_t time_ms, const std::string& level, const std::string& text,
                           std::optional<int64_t> job) {
  return {{"time_ms", time_ms},
          {"level", level},
          {"job", job ? nlohmann::json(*job) : nlohmann::json()},
          {"text", text}};
}

CommandResult RunFarm(const std::string& socket, const std::vector<std::string>& args) {
  std::vector<std::string> full = {RADFARM_CLI_PATH, "--control", socket};
  full.insert(full.end(), args.begin(), args.end());
  return RunCommand(full);
}

}  // namespace radfarm::testing
