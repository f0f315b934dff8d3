// Exit codes of every radfarm command (documented in README.md).
#pragma once

namespace radfarm {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;      // the work failed: I/O error, internal error
inline constexpr int kExitBadInput = 2;     // bad usage, or a scene or job file that is wrong
inline constexpr int kExitUnreachable = 3;  // the master daemon cannot be reached

}  // namespace radfarm
