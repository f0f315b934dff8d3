// The raw figures every benchmark program writes: one JSON document per run, which
// scripts/bench-report turns into the tables and plots of docs/BENCHMARKS*.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bench/machine_info.h"

namespace radfarm::bench {

// The default output of `program`: the source tree's bench/results/PROGRAM.json.
std::string DefaultJsonPath(const std::string& program);

nlohmann::json MachineJson(const MachineInfo& machine);

// Writes `json` (indented) to `path` atomically, making its directory if needed. Throws
// std::runtime_error on failure.
void WriteJson(const std::string& path, const nlohmann::json& json);

}  // namespace radfarm::bench
