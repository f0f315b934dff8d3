// The scaling cases farm_bench runs (bench/farm/scaling_run.h runs one) and their repetitions.
//
// Scaling cases: N = 10, 100, 1000 simulated agents, each a throttled one-thread "office machine"
// of kOfficeRaysPerSecond, with 0 and 20 ms of added one-way latency. The job grows with N (weak
// scaling): shot_rays = N x R x round_seconds, so every round holds round_seconds of work per
// agent whatever N, and the measured losses are the master's (dispatch, round ends), not a job
// too small to share. Capacity cases: agents that answer at once (R = 1e9 rays/s), one round of
// 4096-ray batches, so the master's loop is the only limit: batches/s is its dispatch capacity.
#pragma once

#include <cstdio>
#include <vector>

#include "bench/farm/farm_bench_report.h"

namespace radfarm::bench {

// 4096 rays / 16384 rays/s = 0.25 s: the master's first-round batch (SchedulerOptions::
// default_batch_rays) takes one lease_seconds (radfarmd's default 0.25 s) on such an agent.
inline constexpr double kOfficeRaysPerSecond = 16384;
inline constexpr double kInstantRaysPerSecond = 1e9;

struct SuitePlan {
  std::vector<ScalingRow> rows;  // cases, no samples yet
  int repetitions = 1;
  double round_seconds = 2;
};

SuitePlan MakeSuitePlan(bool quick);

// Runs every case `repetitions` times (case by case within a repetition, so repetitions see the
// machine at different times), printing a line per run. Throws when a run fails.
void RunSuite(SuitePlan& plan, const FarmPrograms& programs, const std::string& scenes_dir,
              const std::string& work_dir);

}  // namespace radfarm::bench
