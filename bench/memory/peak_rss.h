// Peak resident memory of processes: a command run to its end (getrusage of the reaped child) and
// a running daemon (VmHWM in /proc/PID/status).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace radfarm::bench {

struct MeasuredRun {
  int exit_code = -1;
  double seconds = 0;
  uint64_t peak_rss_bytes = 0;
};

// Runs `args` (args[0] the program) with stdout and stderr sent to `log_path`.
MeasuredRun RunMeasured(const std::vector<std::string>& args, const std::string& log_path);

// The peak resident set of a live process, 0 when it cannot be read.
uint64_t PeakRssOf(pid_t pid);

}  // namespace radfarm::bench
