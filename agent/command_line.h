// radfarm-agent's command line (CLI11). ParseCommandLine reads the flags, loads --config FILE if
// given, and merges the two (flags win).
#pragma once

#include <variant>

#include "agent/agent_settings.h"

namespace radfarm::agent {

// Either the settings to run with, or an exit code: 0 after --help or --version, kExitBadInput
// after a usage or config error (already printed on stderr).
using CommandLine = std::variant<AgentSettings, int>;

CommandLine ParseCommandLine(int argc, char** argv);

}  // namespace radfarm::agent
