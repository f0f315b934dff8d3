// LocalTime: the weekday and minute of the day on the machine's local clock, which is what an
// office-hours schedule speaks about. Separate from steady time so tests can fake either.
#pragma once

#include <chrono>
#include <string>

namespace radfarm::idle {

struct LocalTime {
  int weekday = 0;  // 0 = Monday ... 6 = Sunday
  int minute = 0;   // 0 ... 1439 since local midnight

  bool operator==(const LocalTime&) const = default;
};

// `when` on the local time zone (localtime_r; TZ and /etc/localtime apply).
LocalTime LocalTimeOf(std::chrono::system_clock::time_point when);
LocalTime LocalTimeNow();

// "Mon 18:05", for log lines and tests.
std::string Describe(LocalTime time);

}  // namespace radfarm::idle
