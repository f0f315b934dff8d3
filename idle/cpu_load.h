// The CPU load of the *other* processes of the machine: the whole machine's busy time
// (/proc/stat) minus this process's own (getrusage, every thread), as a fraction of all cores.
// An agent rendering on every core must not see its own work as a reason to stop.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm::idle {

// The aggregate "cpu" line of /proc/stat, in clock ticks (USER_HZ), summed over every core.
struct CpuTimes {
  uint64_t busy = 0;   // user + nice + system + irq + softirq + steal
  uint64_t total = 0;  // busy + idle + iowait
};
// Errors say what is wrong with the text ("/proc/stat: no 'cpu' line").
Result<CpuTimes> ParseProcStat(std::string_view text);

// The other processes' share of all cores between two readings, in [0, 1]: (machine busy -
// own) / machine total. Null when no time passed between them.
std::optional<double> OtherCpuFraction(const CpuTimes& before, const CpuTimes& after,
                                       double own_cpu_seconds, double ticks_per_second);

class CpuLoadSource {
 public:
  virtual ~CpuLoadSource() = default;
  // The other processes' load since the previous call (a fraction of all cores); null on the
  // first call or when it cannot be measured (`detail()` says why).
  virtual std::optional<double> OtherLoad() = 0;
  virtual std::string detail() const = 0;
};

// Reads /proc/stat and getrusage(RUSAGE_SELF).
class ProcCpuLoad : public CpuLoadSource {
 public:
  std::optional<double> OtherLoad() override;
  std::string detail() const override { return detail_; }

 private:
  std::optional<CpuTimes> last_times_;
  double last_own_seconds_ = 0;
  std::string detail_;
};

// This process's CPU time so far, user + system, every thread (getrusage).
double OwnCpuSeconds();
// /proc/stat now.
Result<CpuTimes> ReadProcStat();

}  // namespace radfarm::idle
