// Human-readable text for the farm commands: tables of jobs and agents, a job's status, log lines.
// (`--json` prints the master's objects instead; see docs/CONTROL.md.)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/control_objects.h"

namespace radfarm {

// "2026-11-22 06:12:54 UTC"; with_ms adds ".123" before " UTC".
std::string FormatUtcTime(int64_t unix_ms, bool with_ms = false);
// "45s", "3m05s", "2h07m"; rounded up to the second.
std::string FormatDuration(double seconds);
// "12.34 Mrays/s".
std::string FormatRaysPerSecond(double rays_per_second);

// Left-aligned columns two spaces apart; the first row is the header. No trailing spaces.
std::string FormatTable(const std::vector<std::vector<std::string>>& rows);

// What `status` says of a job whose round waits for agents when none is connected (the master's
// `waiting_for_agents`): without it a watch sits at round 0 and "ETA ?" with no hint why.
inline constexpr const char* kNoAgentConnected =
    "no agent connected: start radfarm-agent --master ADDRESS --secret-file FILE (ADDRESS is in "
    "the master's STATE_DIR/listen.addr)";

std::string FormatJobTable(const std::vector<JobInfo>& jobs);
// One "key: value" line per field, aligned.
std::string FormatJobStatus(const JobInfo& job);
std::string FormatAgentTable(const std::vector<AgentInfo>& agents);
std::string FormatEvent(const EventInfo& event);

}  // namespace radfarm
