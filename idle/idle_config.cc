#include "idle/idle_config.h"

#include <limits>
#include <optional>
#include <sstream>

#include "base/result.h"
#include "base/toml_table_reader.h"
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
  const std::string path(file);
  TomlTableReader reader(path, table, std::string(prefix));
  for (const auto& [key, node] : table) {
    const std::string_view name = key.str();
    if (name != "enabled" && name != "user_idle_minutes" && name != "max_other_cpu" &&
        name != "schedule" && name != "poll_seconds") {
      return reader.ErrorFor(name,
                             "is not a key of this table (enabled, user_idle_minutes, "
                             "max_other_cpu, schedule, poll_seconds)");
    }
  }
  // The range checks, located at their keys when present.
  const auto check = [&](std::string_view key, bool present,
                         const std::optional<std::string>& problem) -> Status {
    if (!present || !problem) return Ok{};
    return reader.ErrorFor(key, *problem);
  };

  IdleConfig config;
  bool present = false;
  RADFARM_RETURN_IF_ERROR(reader.Bool("enabled", &config.enabled));

  int64_t minutes = config.user_idle_minutes;
  RADFARM_RETURN_IF_ERROR(reader.Integer("user_idle_minutes", std::numeric_limits<int64_t>::min(),
                                         std::numeric_limits<int64_t>::max(), &minutes, &present));
  RADFARM_RETURN_IF_ERROR(check("user_idle_minutes", present, CheckUserIdleMinutes(minutes)));
  config.user_idle_minutes = static_cast<int>(minutes);

  RADFARM_RETURN_IF_ERROR(
      reader.Real("max_other_cpu", Interval::Any(), &config.max_other_cpu, &present));
  RADFARM_RETURN_IF_ERROR(check("max_other_cpu", present, CheckMaxOtherCpu(config.max_other_cpu)));

  RADFARM_RETURN_IF_ERROR(reader.String("schedule", &config.schedule, &present));
  RADFARM_RETURN_IF_ERROR(check("schedule", present, CheckSchedule(config.schedule)));

  int64_t poll = config.poll_seconds;
  RADFARM_RETURN_IF_ERROR(reader.Integer("poll_seconds", std::numeric_limits<int64_t>::min(),
                                         std::numeric_limits<int64_t>::max(), &poll, &present));
  RADFARM_RETURN_IF_ERROR(check("poll_seconds", present, CheckPollSeconds(poll)));
  config.poll_seconds = static_cast<int>(poll);
  return config;
}

}  // namespace radfarm::idle
