#include "idle/idle_config.h"

#include <optional>
#include <sstream>

#include "base/result.h"
#include "idle/schedule.h"

namespace radfarm::idle {
namespace {

constexpr int kMaxUserIdleMinutes = 7 * 24 * 60;
constexpr int kMaxPollSeconds = 3600;

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// The problem with one key's value ("must be in (0, 1], got 1.5"), or nothing.
std::optional<std::string> CheckUserIdleMinutes(int64_t value) {
  if (value >= 0 && value <= kMaxUserIdleMinutes) return std::nullopt;
  return "must be in [0, " + std::to_string(kMaxUserIdleMinutes) + "], got " +
         std::to_string(value);
}

std::optional<std::string> CheckMaxOtherCpu(double value) {
  if (value > 0 && value <= 1) return std::nullopt;
  return "must be in (0, 1] (a fraction of all cores), got " + Number(value);
}

std::optional<std::string> CheckPollSeconds(int64_t value) {
  if (value >= 1 && value <= kMaxPollSeconds) return std::nullopt;
  return "must be in [1, " + std::to_string(kMaxPollSeconds) + "], got " + std::to_string(value);
}

std::optional<std::string> CheckSchedule(const std::string& value) {
  Result<Schedule> schedule = Schedule::Parse(value);
  if (schedule) return std::nullopt;
  return "is not a schedule: " + schedule.error();
}

// Reads the keys of one table, remembering where each was, for located messages.
class KeyReader {
 public:
  KeyReader(const toml::table& table, std::string_view file, std::string_view prefix)
      : table_(table), file_(file), prefix_(prefix) {}

  Error At(const toml::node& node, std::string_view key, const std::string& what) const {
    std::string location(file_);
    if (node.source().begin.line > 0) {
      location += ":" + std::to_string(node.source().begin.line);
    }
    return Error{location + ": '" + prefix_ + std::string(key) + "' " + what};
  }

  // Type errors name the expected type; absent keys leave *out alone.
  Status Bool(std::string_view key, bool* out) const {
    const toml::node* node = table_.get(key);
    if (!node) return Ok{};
    if (!node->is_boolean()) return At(*node, key, "must be true or false");
    *out = node->as_boolean()->get();
    return Ok{};
  }

  Status Integer(std::string_view key, int64_t* out, bool* present) const {
    const toml::node* node = table_.get(key);
    *present = node != nullptr;
    if (!node) return Ok{};
    if (!node->is_integer()) return At(*node, key, "must be an integer");
    *out = node->as_integer()->get();
    return Ok{};
  }

  Status Real(std::string_view key, double* out, bool* present) const {
    const toml::node* node = table_.get(key);
    *present = node != nullptr;
    if (!node) return Ok{};
    if (node->is_integer()) {
      *out = static_cast<double>(node->as_integer()->get());
    } else if (node->is_floating_point()) {
      *out = node->as_floating_point()->get();
    } else {
      return At(*node, key, "must be a number");
    }
    return Ok{};
  }

  Status String(std::string_view key, std::string* out, bool* present) const {
    const toml::node* node = table_.get(key);
    *present = node != nullptr;
    if (!node) return Ok{};
    if (!node->is_string()) return At(*node, key, "must be a string");
    *out = node->as_string()->get();
    return Ok{};
  }

  // The value's range check, located at its key.
  Status Check(std::string_view key, const std::optional<std::string>& problem) const {
    if (!problem) return Ok{};
    return At(*table_.get(key), key, *problem);
  }

 private:
  const toml::table& table_;
  std::string_view file_;
  std::string prefix_;
};

}  // namespace

Status Validate(const IdleConfig& config, std::string_view prefix) {
  const auto fail = [&](std::string_view key, const std::string& what) {
    return Error{"'" + std::string(prefix) + std::string(key) + "' " + what};
  };
  if (auto problem = CheckUserIdleMinutes(config.user_idle_minutes)) {
    return fail("user_idle_minutes", *problem);
  }
  if (auto problem = CheckMaxOtherCpu(config.max_other_cpu)) {
    return fail("max_other_cpu", *problem);
  }
  if (auto problem = CheckSchedule(config.schedule)) return fail("schedule", *problem);
  if (auto problem = CheckPollSeconds(config.poll_seconds)) return fail("poll_seconds", *problem);
  return Ok{};
}

Result<IdleConfig> ParseIdleConfig(const toml::table& table, std::string_view file,
                                   std::string_view prefix) {
  const KeyReader reader(table, file, prefix);
  for (const auto& [key, node] : table) {
    const std::string_view name = key.str();
    if (name != "enabled" && name != "user_idle_minutes" && name != "max_other_cpu" &&
        name != "schedule" && name != "poll_seconds") {
      return reader.At(node, name,
                       "is not a key of this table (enabled, user_idle_minutes, "
                       "max_other_cpu, schedule, poll_seconds)");
    }
  }

  IdleConfig config;
  bool present = false;
  RADFARM_RETURN_IF_ERROR(reader.Bool("enabled", &config.enabled));

  int64_t minutes = config.user_idle_minutes;
  RADFARM_RETURN_IF_ERROR(reader.Integer("user_idle_minutes", &minutes, &present));
  RADFARM_RETURN_IF_ERROR(
      reader.Check("user_idle_minutes", present ? CheckUserIdleMinutes(minutes) : std::nullopt));
  config.user_idle_minutes = static_cast<int>(minutes);

  RADFARM_RETURN_IF_ERROR(reader.Real("max_other_cpu", &config.max_other_cpu, &present));
  RADFARM_RETURN_IF_ERROR(reader.Check(
      "max_other_cpu", present ? CheckMaxOtherCpu(config.max_other_cpu) : std::nullopt));

  RADFARM_RETURN_IF_ERROR(reader.String("schedule", &config.schedule, &present));
  RADFARM_RETURN_IF_ERROR(
      reader.Check("schedule", present ? CheckSchedule(config.schedule) : std::nullopt));

  int64_t poll = config.poll_seconds;
  RADFARM_RETURN_IF_ERROR(reader.Integer("poll_seconds", &poll, &present));
  RADFARM_RETURN_IF_ERROR(
      reader.Check("poll_seconds", present ? CheckPollSeconds(poll) : std::nullopt));
  config.poll_seconds = static_cast<int>(poll);
  return config;
}

}  // namespace radfarm::idle
