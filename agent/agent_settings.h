// The agent's settings: what the command line and the config file set (agent/README.md lists each
// with its default). AgentOptions holds what one source gave, each value already checked where it
// was read (so errors can name the flag, or the file, line and key); ResolveSettings merges the
// two sources, command line first, and fills in the defaults.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"
#include "idle/idle_config.h"
#include "loop/host_port.h"
#include "loop/log.h"

namespace radfarm::agent {

// WorkQueue's ceiling; also well inside the protocol's kMaxAgentThreads.
inline constexpr unsigned kMaxThreads = 1024;

struct AgentSettings {
  loop::HostPort master;  // where radfarmd listens (unset when master_file is)
  // Non-empty: the master's HOST:PORT is read from this file (its listen.addr) before every
  // connection attempt, so the agent waits for a master that has not started yet and finds one
  // restarted on another port.
  std::string master_file;
  std::string secret_file;  // hex farm secret (protocol/farm_secret.h)
  std::string state_dir;    // empty: scenes are kept in memory only
  unsigned threads = 1;     // batch worker threads
  std::string name;         // the agent's name in the master's logs (IsValidAgentName)
  loop::LogLevel log_level = loop::LogLevel::kInfo;
  double slowdown = 1;                // >= 1: results are held (slowdown - 1) x their compute time
  double exit_when_idle_seconds = 0;  // > 0: exit after this long with no lease (connected or not)
  // The config file's [idle] table. Absent, or enabled = false: work whenever the master has work.
  std::optional<idle::IdleConfig> idle;
  // Non-empty: the idle policy reads the user's activity from this file ("idle" or "busy", see
  // FileUserIdle) instead of logind. A testing and operations aid.
  std::string idle_source;

  bool idle_policy_enabled() const { return idle && idle->enabled; }
};

// One source's settings; absent values are left to the other source or the default.
struct AgentOptions {
  std::optional<loop::HostPort> master;
  std::optional<std::string> master_file;
  std::optional<std::string> secret_file;
  std::optional<std::string> state_dir;
  std::optional<unsigned> threads;
  std::optional<std::string> name;
  std::optional<loop::LogLevel> log_level;
  std::optional<double> slowdown;
  std::optional<double> exit_when_idle_seconds;
  std::optional<idle::IdleConfig> idle;  // the config file only
  std::optional<std::string> idle_source;
};

// Command-line values win over the config file's (a master or master file on the command line
// replaces either in the file). Errors when no source names the master or the secret file, when one
// source gives both a master and a master file, or when an idle source is given without an enabled
// idle policy.
Result<AgentSettings> ResolveSettings(const AgentOptions& command_line, const AgentOptions& file);

// The master's "HOST:PORT"; port 0 is refused (it only means something to a listener). Errors read
// "WHAT: expected HOST:PORT, got 'TEXT' (detail)".
Result<loop::HostPort> ParseMasterAddress(std::string_view text, std::string_view what);

// "debug", "info", "warning", "error".
std::optional<loop::LogLevel> ParseLogLevel(std::string_view text);

// `text` with every character outside [A-Za-z0-9._:@-] replaced by '-', cut to 64 bytes; "agent"
// if that leaves nothing. Used on the host name, which the user did not choose for the protocol.
std::string SanitiseAgentName(std::string_view text);
// The sanitised host name.
std::string DefaultAgentName();
// All cores, within [1, kMaxThreads].
unsigned DefaultThreads();

}  // namespace radfarm::agent
