// Command line of solver_bench.
#pragma once

#include <string>
#include <vector>

namespace radfarm::bench {

struct BenchOptions {
  bool quick = false;      // smoke check: fewer budgets, one repetition, under a minute
  bool raw_only = false;   // only section 2 (the ray loop against raw Embree), printed, no JSON
  std::string json_path;   // where the raw figures go
  std::string scenes_dir;  // where cornell-box.obj and seed-room.obj are
  // --raw-buildings: section 2 alone on these buildings ("AxB" rooms) at the automatic patch size.
  std::vector<std::string> raw_buildings;
};

inline constexpr char kUsage[] =
    "usage: solver_bench [--quick] [--raw-only] [--raw-buildings LIST] [--json PATH]\n"
    "                    [--scenes DIR]\n"
    "  --quick         smoke check: fewer budgets, 1 repetition (under a minute)\n"
    "  --raw-only      only the ray loop against raw Embree, printed (no JSON written)\n"
    "  --raw-buildings LIST  only the ray loop against raw Embree, on the procedural building\n"
    "                  with rooms AxB from LIST (e.g. 2x2,18x18: about 13,000 and 916,000\n"
    "                  patches) at the automatic patch size, as scaling_bench meshes it; prints\n"
    "                  each against raw Embree and against the smallest, writes the JSON\n"
    "  --json PATH     write the figures there (default: bench/results/solver_bench.json)\n"
    "  --scenes DIR    read the scenes from there (default: the source tree's scenes/)\n";

// Returns false (with a message in *error, empty for --help) when the program should stop.
bool ParseBenchOptions(int argc, char** argv, BenchOptions* options, std::string* error);

}  // namespace radfarm::bench
