// Directories only their owner may enter: the master's state, the agents' scene cache. They hold
// job data and scenes other users of the machine have no business reading, and a daemon started
// by hand inherits whatever umask its shell has (022 makes them world-readable).
#pragma once

#include <string>

#include "base/result.h"

namespace radfarm {

// Creates `path` and its missing parents as 0700 whatever the umask. Directories that already
// exist keep their mode (an operator's choice). Errors name the directory that failed.
Status CreatePrivateDirectories(const std::string& path);

}  // namespace radfarm
