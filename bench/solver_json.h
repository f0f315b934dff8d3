// solver_bench's raw figures as JSON (bench/bench_json.h): every point of every sweep, the raw
// throughput and the seed workload, with the settings that produced them.
#pragma once

#include <nlohmann/json.hpp>

#include "bench/bench_report.h"

namespace radfarm::bench {

nlohmann::json SolverBenchJson(const BenchReport& report);
// `solver_bench --raw-buildings`: the ray loop against raw Embree on buildings of each size.
nlohmann::json RawBuildingsJson(const MachineInfo& machine, const std::vector<RawThroughput>& raw,
                                double total_seconds, const std::string& load_average_end);

}  // namespace radfarm::bench
