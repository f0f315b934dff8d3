#include "idle/cpu_load.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace radfarm::idle {

Result<CpuTimes> ParseProcStat(std::string_view text) {
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("cpu ", 0) != 0) continue;
    std::istringstream fields(line.substr(4));
    // user nice system idle iowait irq softirq steal (guest time is already inside user/nice)
    uint64_t value[8] = {};
    int read = 0;
    while (read < 8 && fields >> value[read]) ++read;
    if (read < 4)
      return Error{"/proc/stat: the 'cpu' line has " + std::to_string(read) +
                   " numbers, expected at least 4: '" + line + "'"};
    const uint64_t busy = value[0] + value[1] + value[2] + value[5] + value[6] + value[7];
    return CpuTimes{busy, busy + value[3] + value[4]};
  }
  return Error{"/proc/stat: no 'cpu' line"};
}

std::optional<double> OtherCpuFraction(const CpuTimes& before, const CpuTimes& after,
                                       double own_cpu_seconds, double ticks_per_second) {
  if (after.total <= before.total || ticks_per_second <= 0) return std::nullopt;
  const double total = static_cast<double>(after.total - before.total) / ticks_per_second;
  const double busy = after.busy >= before.busy
                          ? static_cast<double>(after.busy - before.busy) / ticks_per_second
                          : 0.0;
  // Tick accounting and getrusage disagree by a tick or so: clamp instead of going negative.
  return std::clamp((busy - own_cpu_seconds) / total, 0.0, 1.0);
}

double OwnCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

Result<CpuTimes> ReadProcStat() {
  std::ifstream file("/proc/stat");
  if (!file) return Error{"cannot read /proc/stat"};
  std::ostringstream text;
  text << file.rdbuf();
  return ParseProcStat(text.str());
}

std::optional<double> ProcCpuLoad::OtherLoad() {
  Result<CpuTimes> times = ReadProcStat();
  const double own = OwnCpuSeconds();
  if (!times) {
    detail_ = times.error();
    last_times_.reset();
    return std::nullopt;
  }
  std::optional<double> load;
  if (last_times_) {
    load = OtherCpuFraction(*last_times_, *times, own - last_own_seconds_,
                            static_cast<double>(sysconf(_SC_CLK_TCK)));
  }
  last_times_ = *times;
  last_own_seconds_ = own;
  detail_ = load ? "/proc/stat" : "first reading";
  return load;
}

}  // namespace radfarm::idle
