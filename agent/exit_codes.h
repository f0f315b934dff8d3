// Exit codes of radfarm-agent (agent/README.md). They match the radfarm command's where they
// overlap.
#pragma once

namespace radfarm::agent {

inline constexpr int kExitOk = 0;        // a signal, a Drain with exit_after, or --exit-when-idle
inline constexpr int kExitFailure = 1;   // an internal failure (the event loop could not start)
inline constexpr int kExitBadInput = 2;  // bad flags, config file, secret file or state directory

}  // namespace radfarm::agent
