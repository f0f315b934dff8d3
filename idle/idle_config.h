// IdleConfig: the agent's idle policy settings, the [idle] table of agent.conf:
//
//   [idle]
//   enabled = true              # false: work whenever the master has work
//   user_idle_minutes = 10      # no interactive activity for this long (0: only "active" counts)
//   max_other_cpu = 0.5         # other processes' CPU load, a fraction of all cores, in (0, 1]
//   schedule = "Mon-Fri 18:00-08:00, Sat-Sun 00:00-24:00"   # "" = any time (idle/schedule.h)
//   poll_seconds = 5            # how often the CPU load is measured, 1 ... 3600
//
// Every key is optional; the defaults are the values above except schedule (""). Errors name the
// file, the line and the dotted key: "agent.conf:14: 'idle.max_other_cpu' must be in (0, 1], got
// 1.5"; an unknown key is an error too.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm::idle {

struct IdleConfig {
  bool enabled = true;
  int user_idle_minutes = 10;
  double max_other_cpu = 0.5;
  std::string schedule;
  int poll_seconds = 5;
};

// Checks a config built in code (e.g. from command-line flags). Messages name the key with
// `prefix` ("idle." by default): "'idle.poll_seconds' must be in [1, 3600], got 0".
Status Validate(const IdleConfig& config, std::string_view prefix = "idle.");

// Reads the [idle] table (`table`) of the file `file`; `prefix` is its dotted path. Keys absent
// from the table keep their defaults.
Result<IdleConfig> ParseIdleConfig(const toml::table& table, std::string_view file,
                                   std::string_view prefix = "idle.");

}  // namespace radfarm::idle
