// refine_bench's raw figures as JSON (bench/bench_json.h): every scene's reference and rows.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "bench/machine_info.h"
#include "bench/refine/study.h"

namespace radfarm::bench {

struct RefineRun {
  MachineInfo machine;
  std::string load_average_end;
  bool quick = false;
  int timed_runs = 1;            // runs per row whose median time is reported
  bool reference_cache = false;  // references read back from --reference-cache when there
  double total_seconds = 0;
};

nlohmann::json RefineBenchJson(const RefineRun& run, const std::vector<StudyResult>& studies);

}  // namespace radfarm::bench
