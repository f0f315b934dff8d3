#include "agent/agent_settings.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <thread>

#include "protocol/limits.h"

namespace radfarm::agent {
namespace {

bool IsNameCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
         c == '_' || c == ':' || c == '@' || c == '-';
}

template <typename T>
T Pick(const std::optional<T>& first, const std::optional<T>& second, T fallback) {
  if (first) return *first;
  if (second) return *second;
  return fallback;
}

}  // namespace

Result<AgentSettings> ResolveSettings(const AgentOptions& command_line, const AgentOptions& file) {
  AgentSettings settings;
  if (command_line.master && command_line.master_file) {
    return Error{"--master and --master-file: give one of them, not both"};
  }
  if (file.master && file.master_file) {
    return Error{"'master' and 'master_file' in the --config file: give one of them, not both"};
  }
  const bool from_command_line = command_line.master || command_line.master_file;
  const AgentOptions& source = from_command_line ? command_line : file;
  if (source.master) {
    settings.master = *source.master;
  } else if (source.master_file) {
    settings.master_file = *source.master_file;
  } else {
    return Error{
        "no master: give --master HOST:PORT, --master-file FILE, or 'master' or 'master_file' in "
        "the --config file"};
  }
  settings.secret_file = Pick(command_line.secret_file, file.secret_file, std::string());
  if (settings.secret_file.empty()) {
    return Error{"no secret file: give --secret-file FILE or 'secret_file' in the --config file"};
  }
  settings.state_dir = Pick(command_line.state_dir, file.state_dir, std::string());
  settings.threads = Pick(command_line.threads, file.threads, 0u);
  if (settings.threads == 0) settings.threads = DefaultThreads();
  settings.name = Pick(command_line.name, file.name, std::string());
  if (settings.name.empty()) settings.name = DefaultAgentName();
  settings.log_level = Pick(command_line.log_level, file.log_level, loop::LogLevel::kInfo);
  settings.slowdown = Pick(command_line.slowdown, file.slowdown, 1.0);
  settings.exit_when_idle_seconds =
      Pick(command_line.exit_when_idle_seconds, file.exit_when_idle_seconds, 0.0);
  settings.idle = command_line.idle ? command_line.idle : file.idle;
  settings.idle_source = Pick(command_line.idle_source, file.idle_source, std::string());
  if (!settings.idle_source.empty() && !settings.idle_policy_enabled()) {
    return Error{
        "--idle-source (idle_source) needs the idle policy: an [idle] table in the "
        "--config file, with enabled = true"};
  }
  return settings;
}

Result<loop::HostPort> ParseMasterAddress(std::string_view text, std::string_view what) {
  Result<loop::HostPort> address = loop::ParseHostPort(text, what);
  if (address && address->port == 0) {
    return Error{std::string(what) + ": expected HOST:PORT, got '" + std::string(text) +
                 "' (port 0 is not a master's port)"};
  }
  return address;
}

std::optional<loop::LogLevel> ParseLogLevel(std::string_view text) {
  if (text == "debug") return loop::LogLevel::kDebug;
  if (text == "info") return loop::LogLevel::kInfo;
  if (text == "warning") return loop::LogLevel::kWarning;
  if (text == "error") return loop::LogLevel::kError;
  return std::nullopt;
}

std::string SanitiseAgentName(std::string_view text) {
  std::string name(text.substr(0, protocol::kMaxAgentNameBytes));
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !IsNameCharacter(c); }, '-');
  return name.empty() ? "agent" : name;
}

std::string DefaultAgentName() {
  std::array<char, 256> host{};
  if (gethostname(host.data(), host.size() - 1) != 0) return "agent";
  return SanitiseAgentName(host.data());
}

unsigned DefaultThreads() {
  return std::clamp(std::thread::hardware_concurrency(), 1u, kMaxThreads);
}

}  // namespace radfarm::agent
