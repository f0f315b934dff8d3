// Job, agent and event objects as docs/CONTROL.md describes them, the lists of their documented
// keys, and a short way to run `radfarm --control SOCKET ...` for the farm command tests.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm::testing {

extern const std::vector<std::string> kJobKeys;
extern const std::vector<std::string> kAgentKeys;
extern const std::vector<std::string> kEventKeys;

// A job object with every documented key; `round` also sets rays and lowers unshot_fraction.
nlohmann::json JobObject(int64_t id, const std::string& state, uint64_t round = 0);
nlohmann::json AgentObject(int64_t id, const std::string& name);
// An event of the master's log; `job` the job it is about (none: the farm's own).
nlohmann::json EventObject(int64_t time_ms, const std::string& level, const std::string& text,
                           std::optional<int64_t> job = std::nullopt);

// Runs the radfarm binary with `--control socket` in front of `args`.
CommandResult RunFarm(const std::string& socket, const std::vector<std::string>& args);

}  // namespace radfarm::testing
