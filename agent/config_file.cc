#include "agent/config_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "base/result.h"
#include "base/toml_file.h"
#include "idle/idle_config.h"
#include "protocol/message_checks.h"

namespace radfarm::agent {
namespace {

Error ErrorAt(const std::string& path, uint32_t line, const std::string& what) {
  return Error{path + ":" + std::to_string(line) + ": " + what};
}

std::string TypeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a real number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date or time";
  }
}

std::string FormatNumber(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

// Reads one key's value, naming the file, the key's line and the key in every error.
class KeyReader {
 public:
  KeyReader(const std::string& path, const std::string& key, const toml::node& node)
      : path_(path), key_(key), node_(node) {}

  Error Fail(const std::string& what) const { return At("'" + key_ + "' " + what); }
  // "FILE:LINE: what" at this key's line.
  Error At(const std::string& what) const {
    return ErrorAt(path_, node_.source().begin.line, what);
  }

  Result<std::string> String() const {
    if (const auto* value = node_.as_string()) return value->get();
    return Fail("must be a string, not " + TypeName(node_));
  }

  Result<int64_t> Integer(int64_t lo, int64_t hi) const {
    const auto* value = node_.as_integer();
    if (value == nullptr) return Fail("must be an integer, not " + TypeName(node_));
    if (value->get() < lo || value->get() > hi) {
      return Fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                  std::to_string(value->get()));
    }
    return value->get();
  }

  // Integers are accepted where reals are expected. `lo_open`: the bound itself is refused.
  Result<double> Real(double lo, bool lo_open) const {
    double value = 0;
    if (const auto* i = node_.as_integer()) {
      value = static_cast<double>(i->get());
    } else if (const auto* f = node_.as_floating_point()) {
      value = f->get();
    } else {
      return Fail("must be a number, not " + TypeName(node_));
    }
    if (!std::isfinite(value)) return Fail("must be finite");
    if (lo_open ? !(value > lo) : !(value >= lo)) {
      return Fail(std::string("must be ") + (lo_open ? "> " : ">= ") + FormatNumber(lo) + ", got " +
                  FormatNumber(value));
    }
    return value;
  }

  // A path; a relative one is taken relative to the config file's folder.
  Result<std::string> Path() const {
    Result<std::string> text = String();
    if (!text) return text;
    if (text->empty()) return Fail("must not be empty");
    std::filesystem::path path(*text);
    if (path.is_relative()) path = std::filesystem::path(path_).parent_path() / path;
    return path.lexically_normal().string();
  }

 private:
  const std::string& path_;
  const std::string& key_;
  const toml::node& node_;
};

// Stores one key into *options; an error for a key the agent does not know.
Status ReadKey(const KeyReader& reader, const std::string& key, AgentOptions* options) {
  if (key == "master") {
    Result<std::string> text = reader.String();
    RADFARM_RETURN_IF_ERROR(text);
    Result<loop::HostPort> master = ParseMasterAddress(*text, "'master'");
    if (!master) return reader.At(master.error());
    options->master = *master;
  } else if (key == "secret_file" || key == "state_dir") {
    Result<std::string> path = reader.Path();
    RADFARM_RETURN_IF_ERROR(path);
    (key == "secret_file" ? options->secret_file : options->state_dir) = *path;
  } else if (key == "threads") {
    Result<int64_t> threads = reader.Integer(1, kMaxThreads);
    RADFARM_RETURN_IF_ERROR(threads);
    options->threads = static_cast<unsigned>(*threads);
  } else if (key == "name") {
    Result<std::string> name = reader.String();
    RADFARM_RETURN_IF_ERROR(name);
    if (!protocol::IsValidAgentName(*name)) {
      return reader.Fail("must be 1 to 64 characters of A-Z a-z 0-9 . _ : @ -, got '" + *name +
                         "'");
    }
    options->name = *name;
  } else if (key == "log_level") {
    Result<std::string> text = reader.String();
    RADFARM_RETURN_IF_ERROR(text);
    std::optional<loop::LogLevel> level = ParseLogLevel(*text);
    if (!level) return reader.Fail("must be debug, info, warning or error, got '" + *text + "'");
    options->log_level = *level;
  } else if (key == "slowdown") {
    Result<double> slowdown = reader.Real(1, /*lo_open=*/false);
    RADFARM_RETURN_IF_ERROR(slowdown);
    options->slowdown = *slowdown;
  } else if (key == "idle_source") {
    Result<std::string> path = reader.Path();
    RADFARM_RETURN_IF_ERROR(path);
    options->idle_source = *path;
  } else if (key == "exit_when_idle_seconds") {
    Result<double> seconds = reader.Real(0, /*lo_open=*/true);
    RADFARM_RETURN_IF_ERROR(seconds);
    options->exit_when_idle_seconds = *seconds;
  } else {
    return reader.Fail("is not a setting (unknown key)");
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
  AgentOptions options;
  for (const auto& [key, node] : keys) {
    const std::string name(key->str());
    if (name == "idle") {
      // The idle policy's table: idle/idle_config.h reads it, naming "idle.KEY" in its errors.
      const toml::table* idle_table = node->as_table();
      if (idle_table == nullptr) {
        return KeyReader(path, name, *node)
            .Fail("must be a table ([idle]), not " + TypeName(*node));
      }
      Result<idle::IdleConfig> idle = idle::ParseIdleConfig(*idle_table, path);
      RADFARM_RETURN_IF_ERROR(idle);
      options.idle = *idle;
      continue;
    }
    RADFARM_RETURN_IF_ERROR(ReadKey(KeyReader(path, name, *node), name, &options));
  }
  return options;
}

}  // namespace radfarm::agent
