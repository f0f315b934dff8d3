// solver_bench: measures the radiosity solver's speed against its error for every sampler, the
// solver's ray loop against raw Embree, and the seed paper's workload; prints the figures and
// writes them as JSON (bench/results/solver_bench.json; scripts/bench-report makes
// docs/BENCHMARKS.md of it). See bench_options.h for the flags.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_json.h"
#include "bench/bench_options.h"
#include "bench/bench_report.h"
#include "bench/bench_scene.h"
#include "bench/machine_info.h"
#include "bench/raw_throughput.h"
#include "bench/run_benchmark.h"
#include "bench/seed_workload.h"
#include "bench/solver_json.h"
#include "bench/stopwatch.h"
#include "bench/sweep.h"

namespace radfarm::bench {
namespace {

// Patch sizes: the seed room's is its job file's (scenes/seed-room.toml). The Cornell box's job
// file says 25 mm (about 4800 patches); 50 mm (a quarter as many) keeps a 64x reference affordable
// on a small machine, and the samplers compare the same way.
constexpr double kCornellPatchSize = 50;
constexpr double kSeedRoomPatchSize = 0.5;
// The ray loop's big scene: the Cornell box at 5 mm, about 10^5 patches (issue 17's size).
constexpr double kBigCornellPatchSize = 5;
// Its rays: a fixed shot_rays keeps the stored rays of its first 3 rounds near the small box's
// (the automatic 1024 rays per patch would store 10^8 rays), in batches of a few rays from round 1
// on, as a big scene's many weak shooters give.
constexpr uint64_t kBigCornellShotRays = uint64_t{1} << 20;
// The generated building (scenegen/) at its job files' patch size: 2x2 rooms (6,834 patches) in
// --quick runs, 6x6 (60,887) otherwise, with the big box's shot_rays.
constexpr double kBuildingPatchSize = 0.25;

// Section 2 (the ray loop against raw Embree) on the Cornell box, its 10^5-patch version and the
// generated building, on 1 thread and on all cores.
std::vector<RawThroughput> MeasureRayLoop(const BenchScene& cornell, const BenchOptions& options) {
  const BenchScene big =
      LoadBenchScene("cornell-box", options.scenes_dir + "/cornell-box.obj", kBigCornellPatchSize);
  SolverSettings big_settings;
  big_settings.shot_rays = kBigCornellShotRays;
  scenegen::BuildingParams building_params;
  building_params.rooms_x = building_params.rooms_z = options.quick ? 2 : 6;
  const BenchScene building =
      LoadBuildingBenchScene("building", building_params, kBuildingPatchSize);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::vector<unsigned> thread_counts{1};
  if (cores > 1) thread_counts.push_back(cores);
  const int repetitions = options.quick ? 1 : 5;
  std::vector<RawThroughput> out;
  for (const auto& [scene, settings] :
       {std::pair{&cornell, SolverSettings{}}, std::pair{&big, big_settings},
        std::pair{&building, big_settings}}) {
    for (unsigned threads : thread_counts) {
      out.push_back(MeasureRawThroughput(*scene, settings, 3, repetitions, threads));
    }
  }
  return out;
}

std::vector<uint64_t> Ladder(uint64_t first, int rungs) {
  std::vector<uint64_t> ladder;
  for (int i = 0; i < rungs; ++i) ladder.push_back(first << i);
  return ladder;
}

int Run(int argc, char** argv) {
  BenchOptions options;
  std::string error;
  if (!ParseBenchOptions(argc, argv, &options, &error)) {
    std::fprintf(error.empty() ? stdout : stderr, "%s%s%s",
                 error.empty() ? "" : "solver_bench: ", error.empty() ? "" : (error + "\n").c_str(),
                 kUsage);
    return error.empty() ? 0 : 2;
  }
  const Stopwatch total;
  BenchReport report;
  report.machine = ReadMachineInfo(argc, argv);
  report.quick = options.quick;
  std::printf("solver_bench%s: %u CPUs, %s, load %s\n", options.quick ? " --quick" : "",
              report.machine.cpus, report.machine.cpu_model.c_str(),
              report.machine.load_average.c_str());

  SweepConfig config;
  config.repetitions = options.quick ? 1 : 3;
  config.reference_factor = options.quick ? 8 : 64;
  config.grid_steps = options.quick ? std::vector<double>{} : std::vector<double>{8, 4, 2, 1};
  config.grid_converged_steps = options.quick ? std::vector<double>{8} : std::vector<double>{8, 4};
  report.sweep_config = config;
  const int rungs = options.quick ? 3 : 5;

  const BenchScene cornell =
      LoadBenchScene("cornell-box", options.scenes_dir + "/cornell-box.obj", kCornellPatchSize);
  if (options.raw_only) {
    MeasureRayLoop(cornell, options);
    return 0;
  }
  const BenchScene room =
      LoadBenchScene("seed-room", options.scenes_dir + "/seed-room.obj", kSeedRoomPatchSize);

  SweepConfig cornell_config = config;
  cornell_config.shot_rays = Ladder(uint64_t{1} << 17, rungs);
  report.sweeps.push_back(RunSweep(cornell, cornell_config));
  SweepConfig room_config = config;
  room_config.shot_rays = Ladder(uint64_t{1} << 16, rungs);
  report.sweeps.push_back(RunSweep(room, room_config));

  report.raw = MeasureRayLoop(cornell, options);
  report.seed =
      RunSeedWorkload(room, report.sweeps[1].reference, options.quick ? 1 : 5, config.repetitions);

  report.total_seconds = total.Seconds();
  report.load_average_end = ReadLoadAverage();
  WriteJson(options.json_path, SolverBenchJson(report));
  std::printf("wrote %s in %.0f s\n", options.json_path.c_str(), report.total_seconds);
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  return radfarm::bench::RunBenchmark("solver_bench", radfarm::bench::Run, argc, argv);
}
