#include "idle/idle_policy.h"

#include <cmath>
#include <sstream>

#include "base/result.h"
#include "loop/log.h"

namespace radfarm::idle {
namespace {

constexpr std::string_view kComponent = "idle";

std::string Percent(double fraction) {
  return std::to_string(static_cast<int>(std::lround(fraction * 100))) + "%";
}

std::string Duration(std::chrono::seconds duration) {
  const auto seconds = duration.count();
  if (seconds < 120) return std::to_string(seconds) + " s";
  return std::to_string(seconds / 60) + " min";
}

}  // namespace

Result<IdlePolicy> IdlePolicy::Create(const IdleConfig& config, HysteresisSettings hysteresis) {
  RADFARM_RETURN_IF_ERROR(Validate(config));
  Result<Schedule> schedule = Schedule::Parse(config.schedule);
  if (!schedule) return Error{"'idle.schedule' " + schedule.error()};
  const std::chrono::milliseconds hold =
      hysteresis.resume_hold.value_or(std::chrono::seconds(2 * config.poll_seconds));
  return IdlePolicy(config, std::move(schedule).value(), hold, hysteresis.resume_load_fraction);
}

IdlePolicy::IdlePolicy(IdleConfig config, Schedule schedule, std::chrono::milliseconds resume_hold,
                       double resume_load_fraction)
    : config_(std::move(config)),
      schedule_(std::move(schedule)),
      resume_hold_(resume_hold),
      resume_load_fraction_(resume_load_fraction) {}

IdleDecision IdlePolicy::Decide(const IdleSample& sample) {
  if (!config_.enabled) {
    working_ = true;
    return {true, "idle policy disabled"};
  }
  const bool resuming = working_.has_value() && !*working_;
  if (std::optional<std::string> obstacle = Obstacle(sample, resuming)) {
    working_ = false;
    clear_since_.reset();
    return {false, *obstacle};
  }
  if (resuming) {
    if (!clear_since_) clear_since_ = sample.now;
    const auto clear_for = sample.now - *clear_since_;
    if (clear_for < resume_hold_) {
      const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(clear_for);
      return {false, "idle again for " + std::to_string(seconds.count()) + " s of the " +
                         std::to_string(resume_hold_.count() / 1000) + " s before resuming"};
    }
  }
  working_ = true;
  clear_since_.reset();
  return {true, Summary(sample)};
}

std::optional<std::string> IdlePolicy::Obstacle(const IdleSample& sample, bool resuming) {
  const UserIdle& user = sample.user;
  switch (user.state) {
    case UserIdle::State::kActive:
      return "user active";
    case UserIdle::State::kIdle:
      if (user.idle_for < std::chrono::minutes(config_.user_idle_minutes)) {
        return "user idle for " + Duration(user.idle_for) + " of " +
               std::to_string(config_.user_idle_minutes) + " min";
      }
      break;
    case UserIdle::State::kUnknown:
      if (!unknown_user_logged_) {
        unknown_user_logged_ = true;
        loop::LogLine(loop::LogLevel::kWarning, kComponent)
            << "user activity unknown (" << user.detail << "): treating the user as idle";
      }
      break;
  }

  if (!schedule_.Contains(sample.local_time)) {
    return "outside the schedule '" + schedule_.text() + "' (" + Describe(sample.local_time) + ")";
  }

  if (config_.max_other_cpu < 1) {
    if (!sample.other_cpu) {
      if (!unknown_cpu_logged_) {
        unknown_cpu_logged_ = true;
        loop::LogLine(loop::LogLevel::kWarning, kComponent)
            << "other processes' CPU load unknown: not limiting on it";
      }
    } else {
      const double limit = config_.max_other_cpu * (resuming ? resume_load_fraction_ : 1.0);
      if (*sample.other_cpu > limit) {
        return "other processes use " + Percent(*sample.other_cpu) + " of the CPUs (limit " +
               Percent(limit) + ")";
      }
    }
  }
  return std::nullopt;
}

std::string IdlePolicy::Summary(const IdleSample& sample) const {
  std::ostringstream out;
  out << "idle: ";
  switch (sample.user.state) {
    case UserIdle::State::kActive:
      out << "user active";  // not reached: an active user is an obstacle
      break;
    case UserIdle::State::kIdle:
      out << "user idle " << Duration(sample.user.idle_for);
      break;
    case UserIdle::State::kUnknown:
      out << "user activity unknown";
      break;
  }
  if (sample.other_cpu) out << ", other CPU " << Percent(*sample.other_cpu);
  if (!schedule_.always()) out << ", within the schedule";
  return out.str();
}

}  // namespace radfarm::idle
