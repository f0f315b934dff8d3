#include "base/cpu_clock.h"

#include <time.h>

namespace radfarm {
namespace {

double Seconds(clockid_t clock) {
  timespec t{};
  if (clock_gettime(clock, &t) != 0) return 0;
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

}  // namespace

double ProcessCpuSeconds() { return Seconds(CLOCK_PROCESS_CPUTIME_ID); }
double ThreadCpuSeconds() { return Seconds(CLOCK_THREAD_CPUTIME_ID); }

LapClock::LapClock(Scope scope)
    : scope_(scope), wall_(std::chrono::steady_clock::now()), cpu_(Cpu()) {}

double LapClock::Cpu() const {
  return scope_ == kThread ? ThreadCpuSeconds() : ProcessCpuSeconds();
}

Spent LapClock::Lap() {
  const auto now = std::chrono::steady_clock::now();
  const double cpu = Cpu();
  const Spent spent{std::chrono::duration<double>(now - wall_).count(), cpu - cpu_};
  wall_ = now;
  cpu_ = cpu;
  return spent;
}

}  // namespace radfarm
