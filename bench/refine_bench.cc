// refine_bench: adaptive refinement against uniform meshes, samplers and solver settings on the
// Cornell box, the seed paper's room and a hard-shadow scene, each against a fine reference
// (bench/refine/). It writes docs/BENCHMARKS-adaptive.md and docs/benchmarks-adaptive-*.png.
//
// Usage: refine_bench [--quick] [--scene NAME] [--out DIR] [--images DIR]
// [--reference-cache DIR]. Every figure is from one
// run (timings on a shared machine: read ratios, not absolute seconds).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "bench/machine_info.h"
#include "bench/refine/adaptive_report.h"
#include "bench/refine/study.h"
#include "bench/run_benchmark.h"

namespace radfarm::bench {
namespace {

constexpr char kUsage[] =
    "usage: refine_bench [--quick] [--scene NAME] [--out DIR] [--images DIR]\n"
    "                    [--reference-cache DIR]\n"
    "  --quick       smallest meshes and budgets (a smoke run of a minute or two)\n"
    "  --scene NAME  only this scene (cornell-box, seed-room, hard-shadow)\n"
    "  --out DIR     where the report and plots go (default: the source tree's docs/)\n"
    "  --images DIR  also write every row's image and its difference from the reference\n"
    "  --reference-cache DIR  keep the reference solves there and reuse them in later runs\n";

int Run(int argc, char** argv) {
  std::string only;
  StudyOptions options;
  ReportRun run;
  run.out_dir = std::string(RADFARM_SOURCE_DIR) + "/docs";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      options.quick = true;
    } else if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      run.out_dir = argv[++i];
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
  const MachineInfo machine = ReadMachineInfo(argc, argv);
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
  run.reference_cache = !options.reference_cache.empty();
  run.machine = machine.date + ", " + std::to_string(machine.cpus) + " CPUs (" + machine.cpu_model +
                "), load " + machine.load_average + " at start, " + ReadLoadAverage() +
                " at end, " + machine.compiler;
  run.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteAdaptiveReport(run, studies);
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  return radfarm::bench::RunBenchmark("refine_bench", radfarm::bench::Run, argc, argv);
}
