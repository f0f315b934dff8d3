// Everything farm_bench measured, for the printed summary and BENCHMARKS-farm.md.
#pragma once

#include <string>
#include <vector>

#include "bench/farm/real_compute.h"
#include "bench/farm/scaling_run.h"
#include "bench/machine_info.h"

namespace radfarm::bench {

// One scaling case and its repetitions.
struct ScalingRow {
  std::string group;  // "scaling" (throttled agents) or "capacity" (agents that answer at once)
  ScalingCase config;
  std::vector<ScalingSample> samples;
};

struct FarmBenchReport {
  MachineInfo machine;
  bool quick = false;
  std::string radfarmd;  // the master binary measured
  bool has_real = false;
  RealComputeResult real;
  std::vector<ScalingRow> scaling;
  int repetitions = 1;
  double round_seconds = 0;  // scaling job: one round's work per agent
  uint64_t open_file_limit = 0;
  double total_seconds = 0;
  std::string load_average_end;
};

}  // namespace radfarm::bench
