#include "idle/local_time.h"

#include <ctime>
#include <iomanip>
#include <sstream>

namespace radfarm::idle {
namespace {

constexpr const char* kDayNames[] = {"Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun"};

}  // namespace

LocalTime LocalTimeOf(std::chrono::system_clock::time_point when) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(when);
  std::tm local{};
  localtime_r(&seconds, &local);
  return LocalTime{(local.tm_wday + 6) % 7, local.tm_hour * 60 + local.tm_min};
}

LocalTime LocalTimeNow() { return LocalTimeOf(std::chrono::system_clock::now()); }

std::string Describe(LocalTime time) {
  std::ostringstream out;
  out << kDayNames[time.weekday % 7] << ' ' << std::setfill('0') << std::setw(2) << time.minute / 60
      << ':' << std::setw(2) << time.minute % 60;
  return out.str();
}

}  // namespace radfarm::idle
