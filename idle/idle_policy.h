// IdlePolicy: may this agent take work now? Pure decision logic: it is handed one sample of its
// sources at a time (user idle time, other processes' CPU load, local time of day) together with
// the steady time of the sample, and keeps only the state its hysteresis needs.
//
//   working --(user active, or idle less than user_idle_minutes,
//              or outside the schedule,
//              or other CPU load > max_other_cpu)-------------------> paused    (at once)
//   paused  --(every condition holds, CPU load <= 0.8 x max_other_cpu,
//              continuously for resume_hold)--------------------------> working
//
// Stopping is immediate because a returning user must get the machine back within a second;
// resuming waits, so a load hovering at the limit or a user who glances at the screen does not
// make the agent flap. The very first decision needs no hold.
//
// Unknown sources do not stop work: an unknown user (no logind) counts as idle, an unknown CPU
// load as low; each is logged once (a warning naming why) so the operator knows the policy is
// weaker than configured.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "base/result.h"
#include "idle/idle_config.h"
#include "idle/local_time.h"
#include "idle/schedule.h"
#include "idle/user_idle.h"

namespace radfarm::idle {

struct IdleSample {
  std::chrono::steady_clock::time_point now;
  UserIdle user;
  std::optional<double> other_cpu;  // fraction of all cores; null: unknown
  LocalTime local_time;
};

struct IdleDecision {
  bool may_work = false;
  std::string reason;  // one line for logs and status: "user active", "idle 14 min, CPU 3%"
};

struct HysteresisSettings {
  // How long every condition must hold before a paused agent works again. Default: two CPU
  // measurements (2 x poll_seconds).
  std::optional<std::chrono::milliseconds> resume_hold;
  // A paused agent resumes only below this fraction of max_other_cpu.
  double resume_load_fraction = 0.8;
};

class IdlePolicy {
 public:
  // `config` is validated here (Validate()); errors name the key.
  static Result<IdlePolicy> Create(const IdleConfig& config, HysteresisSettings hysteresis = {});

  IdleDecision Decide(const IdleSample& sample);

  const IdleConfig& config() const { return config_; }
  std::chrono::milliseconds resume_hold() const { return resume_hold_; }

 private:
  IdlePolicy(IdleConfig config, Schedule schedule, std::chrono::milliseconds resume_hold,
             double resume_load_fraction);

  // Why the agent may not work with this sample, or nothing. `resuming` applies the stricter
  // load limit of a paused agent.
  std::optional<std::string> Obstacle(const IdleSample& sample, bool resuming);
  std::string Summary(const IdleSample& sample) const;

  IdleConfig config_;
  Schedule schedule_;
  std::chrono::milliseconds resume_hold_;
  double resume_load_fraction_;

  std::optional<bool> working_;  // null before the first decision
  std::optional<std::chrono::steady_clock::time_point> clear_since_;
  bool unknown_user_logged_ = false;
  bool unknown_cpu_logged_ = false;
};

}  // namespace radfarm::idle
