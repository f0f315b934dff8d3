// farm_bench's raw figures as JSON (bench/bench_json.h): every repetition of every real setup and
// every simulated case, with the cases' settings.
#pragma once

#include <nlohmann/json.hpp>

#include "bench/farm/farm_bench_report.h"

namespace radfarm::bench {

nlohmann::json FarmBenchJson(const FarmBenchReport& report);

}  // namespace radfarm::bench
