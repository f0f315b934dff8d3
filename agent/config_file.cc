#include "agent/config_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "base/diagnostic.h"
#include "base/result.h"
#include "base/toml_file.h"
#include "base/toml_table_reader.h"
#include "idle/idle_config.h"
#include "protocol/message_checks.h"

namespace radfarm::agent {
namespace {

// A path; a relative one is taken relative to the config file's folder.
Status ReadPath(TomlTableReader& reader, const std::string& path, const std::string& key,
                std::optional<std::string>* out) {
  std::string text;
  RADFARM_RETURN_IF_ERROR(reader.String(key, &text));
  if (text.empty()) return reader.ErrorFor(key, "must not be empty");
  std::filesystem::path resolved(text);
  if (resolved.is_relative()) resolved = std::filesystem::path(path).parent_path() / resolved;
  *out = resolved.lexically_normal().string();
  return Ok{};
}

// Stores one key into *options; an error for a key the agent does not know. `line` is the key's.
Status ReadKey(TomlTableReader& reader, const std::string& path, const std::string& key,
               uint32_t line, AgentOptions* options) {
  if (key == "master") {
    std::string text;
    RADFARM_RETURN_IF_ERROR(reader.String(key, &text));
    Result<loop::HostPort> master = ParseMasterAddress(text, "'master'");
    if (!master) return ErrorAt(path, line, master.error());
    options->master = *master;
  } else if (key == "master_file") {
    RADFARM_RETURN_IF_ERROR(ReadPath(reader, path, key, &options->master_file));
  } else if (key == "secret_file") {
    RADFARM_RETURN_IF_ERROR(ReadPath(reader, path, key, &options->secret_file));
  } else if (key == "state_dir") {
    RADFARM_RETURN_IF_ERROR(ReadPath(reader, path, key, &options->state_dir));
  } else if (key == "idle_source") {
    RADFARM_RETURN_IF_ERROR(ReadPath(reader, path, key, &options->idle_source));
  } else if (key == "threads") {
    int64_t threads = 0;
    RADFARM_RETURN_IF_ERROR(reader.Integer(key, 1, kMaxThreads, &threads));
    options->threads = static_cast<unsigned>(threads);
  } else if (key == "name") {
    std::string name;
    RADFARM_RETURN_IF_ERROR(reader.String(key, &name));
    if (!protocol::IsValidAgentName(name)) {
      return reader.ErrorFor(
          key, "must be 1 to 64 characters of A-Z a-z 0-9 . _ : @ -, got '" + name + "'");
    }
    options->name = name;
  } else if (key == "log_level") {
    std::string text;
    RADFARM_RETURN_IF_ERROR(reader.String(key, &text));
    std::optional<loop::LogLevel> level = ParseLogLevel(text);
    if (!level) {
      return reader.ErrorFor(key, "must be debug, info, warning or error, got '" + text + "'");
    }
    options->log_level = *level;
  } else if (key == "slowdown") {
    double slowdown = 0;
    RADFARM_RETURN_IF_ERROR(reader.Real(key, Interval::AtLeast(1), &slowdown));
    options->slowdown = slowdown;
  } else if (key == "exit_when_idle_seconds") {
    double seconds = 0;
    RADFARM_RETURN_IF_ERROR(reader.Real(key, Interval::Above(0), &seconds));
    options->exit_when_idle_seconds = seconds;
  } else {
    return reader.ErrorFor(key, "is not a setting (unknown key)");
  }
  return Ok{};
}

}  // namespace

Result<AgentOptions> LoadConfigFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path + ": cannot read the config file: " + std::strerror(errno)};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Error{path + ": cannot read the config file"};
  Result<toml::table> table = ParseToml(path, text.str());
  RADFARM_RETURN_IF_ERROR(table);

  // Keys in file order, so the first bad line is the one reported.
  std::vector<std::pair<const toml::key*, const toml::node*>> keys;
  for (const auto& [key, node] : *table) keys.emplace_back(&key, &node);
  std::sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
    return a.first->source().begin.line < b.first->source().begin.line;
  });
  TomlTableReader reader(path, *table, "");
  AgentOptions options;
  for (const auto& [key, node] : keys) {
    const std::string name(key->str());
    if (name == "idle") {
      // The idle policy's table: idle/idle_config.h reads it, naming "idle.KEY" in its errors.
      const toml::table* idle_table = node->as_table();
      if (idle_table == nullptr) {
        return reader.ErrorFor(name, "must be a table ([idle]), not " + TomlTypeName(*node));
      }
      Result<idle::IdleConfig> idle = idle::ParseIdleConfig(*idle_table, path);
      RADFARM_RETURN_IF_ERROR(idle);
      options.idle = *idle;
      continue;
    }
    RADFARM_RETURN_IF_ERROR(ReadKey(reader, path, name, node->source().begin.line, &options));
  }
  return options;
}

}  // namespace radfarm::agent
