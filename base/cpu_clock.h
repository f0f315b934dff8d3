// Wall and CPU seconds, for reports of where time went (a job's timeline): the CPU seconds of this
// process or of the calling thread, and a clock that hands out what was spent since its last lap.
#pragma once

#include <chrono>

namespace radfarm {

double ProcessCpuSeconds();
double ThreadCpuSeconds();

struct Spent {
  double wall_seconds = 0;
  double cpu_seconds = 0;
};

// Wall and CPU seconds since construction or the last Lap. `thread`: the calling thread's CPU
// (every Lap from the thread that made the clock), else the whole process's.
class LapClock {
 public:
  enum Scope { kProcess, kThread };
  explicit LapClock(Scope scope = kProcess);
  Spent Lap();

 private:
  double Cpu() const;

  Scope scope_;
  std::chrono::steady_clock::time_point wall_;
  double cpu_;
};

}  // namespace radfarm
