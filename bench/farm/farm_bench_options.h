// Command line of farm_bench.
#pragma once

#include <cstddef>
#include <string>

namespace radfarm::bench {

struct FarmBenchOptions {
  bool quick = false;     // smoke check: small jobs, fewer cases, one repetition, under a minute
  bool real = true;       // part 1: real processes, real compute
  bool simulated = true;  // part 2: simulated agents
  bool capacity_only = false;  // of part 2, only the dispatch capacity cases
  int repetitions = 0;         // 0: 5 real / 3 simulated (full), 1 (quick)
  size_t agents = 0;           // run only the simulated cases with this many agents (0: all)
  std::string json_path;       // where the figures go
  std::string scenes_dir;      // where cornell-box.toml and furnace.obj are
  std::string radfarmd;        // the master under test (default: the one built with farm_bench)
};

inline constexpr char kFarmBenchUsage[] =
    "usage: farm_bench [--quick] [--only real|sim|capacity] [--agents N] [--repetitions N]\n"
    "                  [--radfarmd PATH] [--json PATH] [--scenes DIR]\n"
    "  Measures the farm: the Cornell box solved by `radfarm render` against radfarmd with 1 and\n"
    "  2 real agents on loopback, then radfarmd with 10, 100 and 1000 simulated agents (with and\n"
    "  without added latency). Prints the figures and writes them as JSON.\n"
    "  --quick         smoke check: small jobs, fewer cases, 1 repetition (under a minute)\n"
    "  --only PART     run only `real` (real agents), `sim` (simulated agents) or `capacity`\n"
    "                  (the simulated dispatch capacity cases: the master's batches/s)\n"
    "  --agents N      run only the simulated cases with N agents (for profiling the master)\n"
    "  --repetitions N runs per case (default: 5 real, 3 simulated; --quick: 1)\n"
    "  --radfarmd PATH the master to measure (default: the radfarmd built with farm_bench), e.g.\n"
    "                  a copy of an older build, to compare two versions\n"
    "  --json PATH     write the figures there (default: bench/results/farm_bench.json)\n"
    "  --scenes DIR    read the scenes from there (default: the source tree's scenes/)\n";

// Returns false (with a message in *error, empty for --help) when the program should stop.
bool ParseFarmBenchOptions(int argc, char** argv, FarmBenchOptions* options, std::string* error);

}  // namespace radfarm::bench
