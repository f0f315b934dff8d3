// Command line of office_bench.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace radfarm::bench {

struct OfficeOptions {
  std::vector<std::string> jobs;                 // job files; default the Cornell box
  std::vector<size_t> agents = {1, 2, 4, 6, 8};  // farm sizes N
  double share = 0.3;                            // of one core, for every process
  std::vector<std::string> flags;                // --rays / --patch-size, for render and submit
  std::chrono::seconds timeout{3600};            // for any one command or job
  std::string json_path;
  std::string keep;  // outputs and logs here instead of a temporary directory
};

inline constexpr char kOfficeUsage[] =
    "usage: office_bench [--job FILE]... [--agents LIST] [--share S] [--rays N]\n"
    "                    [--patch-size P] [--timeout SECONDS] [--json PATH] [--keep DIR]\n"
    "  An office of small machines emulated on this box: every process in a cpu cgroup of its\n"
    "  own (cgroup v1 cpu or v2 cpu.max; skipped where neither is writable, which needs root\n"
    "  or a delegated group) capped at S of a core. One machine is `radfarm render --threads 1`;\n"
    "  the farm is radfarmd, N radfarm-agents with --threads 1 and the radfarm client, timed\n"
    "  from `radfarm submit` to `radfarm fetch` done. Prints per job N, ideal time (one machine\n"
    "  / N), real time, speedup, efficiency and each part's CPU seconds; checks image.png,\n"
    "  radiosity.ply, lit.glb and patches.csv are render's byte for byte (exit 1 if not); fits\n"
    "  T(N) = S + P/N and predicts 100 and 1,000 machines.\n"
    "  --job FILE       a job file, repeatable (default: scenes/cornell-box.toml). The seed\n"
    "                   paper's room: scenes/seed-room.toml. A building job: `radfarm building\n"
    "                   --rooms 2x2 --out DIR` writes DIR/building.toml to give here\n"
    "  --agents LIST    farm sizes N (default 1,2,4,6,8); an N whose N + 2 caps exceed this\n"
    "                   box's CPUs is skipped and said so\n"
    "  --share S        cap of every process in cores, at least 0.1 (default 0.3)\n"
    "  --rays N, --patch-size P  given to both render and submit (default: the job's own)\n"
    "  --timeout SECONDS  kill any one command or job after this long (default 3600)\n"
    "  --json PATH      write the figures there (default: bench/results/office_bench.json)\n"
    "  --keep DIR       keep the outputs and logs under DIR\n";

// Returns false (with a message in *error, empty for --help) when the program should stop.
bool ParseOfficeOptions(int argc, char** argv, OfficeOptions* options, std::string* error);

}  // namespace radfarm::bench
