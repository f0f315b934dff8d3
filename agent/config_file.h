// The agent's TOML config file (--config FILE): the command line's settings as top-level keys.
//
//   master = "farm.example.org:7070"    # HOST:PORT of radfarmd
//   secret_file = "farm.key"            # relative paths are relative to the config file's folder
//   state_dir = "/var/lib/radfarm-agent"
//   threads = 8                         # integer in [1, 1024]
//   name = "office-12"                  # 1..64 of [A-Za-z0-9._:@-]
//   log_level = "info"                  # debug | info | warning | error
//   slowdown = 1.0                      # >= 1
//   exit_when_idle_seconds = 600        # > 0
//   idle_source = "/run/user-idle"      # a file saying "idle" or "busy" instead of logind (tests)
//
//   [idle]                              # the idle policy: idle/idle_config.h has its keys
//   user_idle_minutes = 10
//
// Every key is optional; any other key is an error. Errors are one line naming the file, the line
// and the key: "agent.toml:4: 'threads' must be in [1, 1024], got 0".
#pragma once

#include <string>

#include "agent/agent_settings.h"
#include "base/result.h"

namespace radfarm::agent {

Result<AgentOptions> LoadConfigFile(const std::string& path);

}  // namespace radfarm::agent
