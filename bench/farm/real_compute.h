// The farm with real compute on this machine: the same job solved by `radfarm render` (embedded,
// 2 threads) and by radfarmd with real radfarm-agent processes on loopback (1 agent x 2 threads,
// 2 agents x 1 thread). Rays/s of each, the farm/embedded ratios and whether the farm's
// patches.csv is byte-identical to render's.
#pragma once

#include <string>
#include <vector>

#include "bench/farm/farm_checks.h"

namespace radfarm::bench {

struct RealComputeConfig {
  FarmPrograms programs;
  std::string job_file;                // a .toml job (scenes/cornell-box.toml)
  std::vector<std::string> overrides;  // extra flags for both render and submit
  int repetitions = 3;
  std::string work_dir;  // scratch space (must exist)
};

// One setup's runs.
struct RealComputeSetup {
  std::string name;                     // "embedded", "farm 1x2", "farm 2x1"
  std::string detail;                   // how it ran, for the report
  std::vector<double> rays_per_second;  // job rays / solve seconds, one per repetition
  std::vector<double> solve_seconds;    // stats.json "seconds"
  std::vector<double> wall_seconds;     // see RealComputeResult
  uint64_t rays = 0;                    // the job's rays (the same every run: determinism)
  uint32_t rounds = 0;
  bool patches_identical = true;  // every run's patches.csv equals render's (farm only)
  // CPU seconds, one per repetition: embedded, the render process's whole run; a farm,
  // radfarmd's and the agents' from the submission to the job's end (on loopback the farm's
  // processes share the machine's CPUs: docs/BENCHMARKS-farm.md, "Where the CPU goes").
  std::vector<double> cpu_seconds;         // embedded: radfarm render; a farm: radfarmd
  std::vector<double> agents_cpu_seconds;  // a farm's agents together
};

struct RealComputeResult {
  std::vector<RealComputeSetup> setups;  // [0] is embedded
  std::string job;                       // the job as run, for the report
};

// Runs every setup `repetitions` times, interleaved (E, F1, F2, E, ...) so that they see the same
// machine load. Throws std::runtime_error when a run fails.
RealComputeResult RunRealCompute(const RealComputeConfig& config);

}  // namespace radfarm::bench
