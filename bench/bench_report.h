// Everything one benchmark run measured: what report.cc writes and conclusions.cc judges.
#pragma once

#include <string>
#include <vector>

#include "bench/machine_info.h"
#include "bench/raw_throughput.h"
#include "bench/seed_workload.h"
#include "bench/sweep.h"

namespace radfarm::bench {

struct BenchReport {
  MachineInfo machine;
  bool quick = false;
  double total_seconds = 0;
  std::string load_average_end;    // /proc/loadavg when the measurements were done
  SweepConfig sweep_config;        // shared by the scenes except for the ladder
  std::vector<SceneSweep> sweeps;  // section 1, one per scene
  RawThroughput raw;               // section 2
  SeedWorkload seed;               // sections 3 and 4
  std::vector<std::string> plots;  // PNG file names, relative to the report, one per sweep
};

}  // namespace radfarm::bench
