// farm_bench: the farm's scaling benchmark. Part 1 solves the Cornell box with `radfarm render`
// and with radfarmd plus real radfarm-agent processes on loopback; part 2 runs radfarmd with 10,
// 100 and 1000 simulated agents (farmsim/). Prints the figures and writes them as JSON
// (bench/results/farm_bench.json; scripts/bench-report makes docs/BENCHMARKS-farm.md of it). See
// farm_bench_options.h.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "bench/bench_json.h"
#include "bench/farm/farm_bench_options.h"
#include "bench/farm/farm_json.h"
#include "bench/farm/scaling_suite.h"
#include "bench/run_benchmark.h"
#include "bench/stopwatch.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

// The real setups' medians, one line each: Mrays/s, the median of the per-repetition ratios to
// embedded, and whether every run's patches.csv matched render's.
void PrintRealSummary(const FarmBenchReport& report) {
  if (!report.has_real) return;
  const RealComputeSetup& embedded = report.real.setups[0];
  std::printf("\n%-28s %8s %8s %-11s %s\n", "setup", "Mrays/s", "ratio", "patches.csv",
              "CPU s (render; radfarmd + agents)");
  for (const RealComputeSetup& s : report.real.setups) {
    std::vector<double> ratios;
    for (size_t i = 0; i < s.rays_per_second.size() && i < embedded.rays_per_second.size(); ++i) {
      ratios.push_back(s.rays_per_second[i] / embedded.rays_per_second[i]);
    }
    std::printf("%-28s %8.2f %7.1f%% %-11s ", s.name.c_str(), Median(s.rays_per_second) / 1e6,
                ratios.empty() ? 0 : 100 * Median(ratios),
                &s == &embedded       ? "reference"
                : s.patches_identical ? "identical"
                                      : "DIFFERENT");
    if (&s == &embedded) {
      std::printf("%.2f\n", Median(s.cpu_seconds));
    } else {
      std::printf("%.2f + %.2f\n", Median(s.cpu_seconds), Median(s.agents_cpu_seconds));
    }
  }
  // What encryption costs: the sealed farm against the same farm with frames in clear (but
  // authenticated), paired by repetition (docs/PROTOCOL.md, "Sealed frames").
  const RealComputeSetup& sealed = report.real.setups[1];
  const RealComputeSetup& clear = report.real.setups[3];
  std::vector<double> ratios;
  for (size_t i = 0; i < sealed.rays_per_second.size() && i < clear.rays_per_second.size(); ++i) {
    ratios.push_back(sealed.rays_per_second[i] / clear.rays_per_second[i]);
  }
  if (!ratios.empty()) {
    std::printf(
        "encryption: farm 1 x 2 encrypted / not encrypted, median of %zu paired ratios: "
        "%.1f%%\n",
        ratios.size(), 100 * Median(ratios));
  }
}

int Run(int argc, char** argv) {
  FarmBenchOptions options;
  std::string error;
  if (!ParseFarmBenchOptions(argc, argv, &options, &error)) {
    if (error.empty()) {
      std::fputs(kFarmBenchUsage, stdout);
      return 0;
    }
    std::fprintf(stderr, "farm_bench: %s\n%s", error.c_str(), kFarmBenchUsage);
    return 2;
  }
  const Stopwatch total;
  const FarmPrograms programs{options.radfarmd, RADFARM_AGENT_PATH, RADFARM_CLI_PATH};
  FarmBenchReport report;
  report.machine = ReadMachineInfo(argc, argv);
  report.quick = options.quick;
  report.radfarmd = options.radfarmd;
  report.open_file_limit = RaiseOpenFileLimit();
  std::printf("farm_bench%s: %u CPUs, %s, load %s, open files %llu\n",
              options.quick ? " --quick" : "", report.machine.cpus,
              report.machine.cpu_model.c_str(), report.machine.load_average.c_str(),
              static_cast<unsigned long long>(report.open_file_limit));
  const testing::TempDir scratch("farm_bench");

  if (options.real) {
    RealComputeConfig config;
    config.programs = programs;
    config.job_file = options.scenes_dir + "/cornell-box.toml";
    if (options.quick) config.overrides = {"--tolerance", "0.01"};
    config.repetitions = options.repetitions > 0 ? options.repetitions : options.quick ? 1 : 5;
    config.work_dir = scratch.path();
    std::printf("real compute: %s, %d repetitions\n", config.job_file.c_str(), config.repetitions);
    report.real = RunRealCompute(config);
    report.has_real = true;
  }
  if (options.simulated) {
    SuitePlan plan = MakeSuitePlan(options.quick);
    if (options.repetitions > 0) plan.repetitions = options.repetitions;
    if (options.capacity_only) {
      std::erase_if(plan.rows, [](const ScalingRow& row) { return row.group != "capacity"; });
    }
    if (options.agents > 0) {
      std::erase_if(plan.rows,
                    [&](const ScalingRow& row) { return row.config.agents != options.agents; });
    }
    std::printf("simulated agents: %zu cases, %d repetitions\n", plan.rows.size(),
                plan.repetitions);
    RunSuite(plan, programs, options.scenes_dir, scratch.path());
    report.scaling = std::move(plan.rows);
    report.repetitions = plan.repetitions;
    report.round_seconds = plan.round_seconds;
  }

  report.total_seconds = total.Seconds();
  report.load_average_end = ReadLoadAverage();
  PrintRealSummary(report);
  WriteJson(options.json_path, FarmBenchJson(report));
  std::printf("wrote %s in %.0f s\n", options.json_path.c_str(), report.total_seconds);
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  return radfarm::bench::RunBenchmark("farm_bench", radfarm::bench::Run, argc, argv);
}
