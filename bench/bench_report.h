// Everything one solver_bench run measured, written out by solver_json.h.
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
  std::vector<SceneSweep> sweeps;  // speed against error, one per scene
  std::vector<RawThroughput>
      raw;            // the solver's ray loop against raw Embree, per scene and threads
  SeedWorkload seed;  // the seed paper's workload and equal time on its room
};

}  // namespace radfarm::bench
