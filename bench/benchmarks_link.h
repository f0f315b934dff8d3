// The line of docs/BENCHMARKS.md (solver_bench's report) that points at docs/BENCHMARKS-farm.md
// (farm_bench's). Both programs write it: solver_bench rewrites BENCHMARKS.md wholesale and keeps
// it; farm_bench adds it when it is missing.
#pragma once

namespace radfarm::bench {

inline constexpr char kFarmBenchmarksLink[] =
    "Farm scaling (radfarmd with real and simulated agents): "
    "[BENCHMARKS-farm.md](BENCHMARKS-farm.md), written by `farm_bench`.";

}  // namespace radfarm::bench
