// refine_bench: adaptive refinement against uniform meshes, samplers and solver settings on the
// Cornell box, the seed paper's room, a hard-shadow scene and the 2 x 2 building, each against a
// fine reference (bench/refine/). It prints a line per row and writes the figures as JSON
// (bench/results/refine_bench.json; scripts/bench-report makes docs/BENCHMARKS-adaptive.md of it).
// Every figure is from one run (timings on a shared machine: read ratios, not absolute seconds).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/refine/refine_json.h"
#include "bench/refine/study.h"
#include "bench/run_benchmark.h"

namespace radfarm::bench {
namespace {

constexpr char kUsage[] =
    "usage: refine_bench [--quick] [--scene NAME] [--json PATH] [--images DIR]\n"
    "                    [--reference-cache DIR]\n"
    "  --quick       smallest meshes and budgets (a smoke run of a minute or two)\n"
    "  --scene NAME  only this scene (cornell-box, seed-room, hard-shadow, building-2x2)\n"
    "  --json PATH   write the figures there (default: bench/results/refine_bench.json)\n"
    "  --images DIR  also write every row's image and its difference from the reference\n"
    "  --reference-cache DIR  keep the reference solves there and reuse them in later runs\n";

int Run(int argc, char** argv) {
  std::string only;
  StudyOptions options;
  std::string json_path = DefaultJsonPath("refine_bench");
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      options.quick = true;
    } else if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else if (std::strcmp(argv[i], "--json") == 0 && i + 1 < argc) {
      json_path = argv[++i];
    } else if (std::strcmp(argv[i], "--images") == 0 && i + 1 < argc) {
      options.images_dir = argv[++i];
    } else if (std::strcmp(argv[i], "--reference-cache") == 0 && i + 1 < argc) {
      options.reference_cache = argv[++i];
    } else if (std::strcmp(argv[i], "--help") == 0) {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      std::fputs(kUsage, stderr);
      return 2;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  RefineRun run;
  run.machine = ReadMachineInfo(argc, argv);
  std::vector<StudyResult> studies;
  for (const StudyScene& scene : StudyScenes(options.quick)) {
    if (!only.empty() && scene.name != only) continue;
    studies.push_back(RunStudy(scene, options));
  }
  if (studies.empty()) {
    std::fprintf(stderr, "refine_bench: no scene named %s\n", only.c_str());
    return 2;
  }
  run.quick = options.quick;
  run.timed_runs = TimedRuns(options);
  run.reference_cache = !options.reference_cache.empty();
  run.load_average_end = ReadLoadAverage();
  run.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteJson(json_path, RefineBenchJson(run, studies));
  std::printf("wrote %s in %.0f s\n", json_path.c_str(), run.total_seconds);
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  return radfarm::bench::RunBenchmark("refine_bench", radfarm::bench::Run, argc, argv);
}
