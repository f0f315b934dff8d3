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
#include <tuple>
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
// The ray loop's big scene: the Cornell box at 5 mm, about 10^5 patches.
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

// At most this many of a building's planned rays are traced (every k-th batch; about 2 GB of
// stored rays): a default solve's first 3 rounds at 10^6 patches plan several hundred million.
constexpr uint64_t kRawBuildingMaxRays = 16'000'000;

// --raw-buildings: the first 3 rounds of a default solve (automatic shot_rays, as `radfarm
// render` would run it) of each building at the automatic patch size, as scaling_bench meshes
// it; each against raw Embree, and its tracer against the first building's on as many threads.
int RunRawBuildings(const BenchOptions& options, const MachineInfo& machine) {
  const Stopwatch total;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::vector<unsigned> thread_counts{1};
  if (cores > 1) thread_counts.push_back(cores);
  const int repetitions = options.quick ? 1 : 3;
  std::vector<RawThroughput> out;
  for (const std::string& rooms : options.raw_buildings) {
    scenegen::BuildingParams params;
    std::tie(params.rooms_x, params.rooms_z) = scenegen::ParseRoomCounts(rooms).value();  // checked
    const BenchScene building = LoadBuildingBenchScene("building-" + rooms, params, 0);
    std::printf("building %s: %zu patches, meshed in %.1f s\n", rooms.c_str(),
                building.patches().patches.size(), building.load_seconds);
    for (unsigned threads : thread_counts) {
      out.push_back(MeasureRawThroughput(building, SolverSettings{}, 3, repetitions, threads,
                                         kRawBuildingMaxRays));
    }
  }
  std::printf("\n%-16s %9s %7s %11s %11s %9s %9s %8s %12s\n", "scene", "patches", "threads", "rays",
              "of planned", "raw Mr/s", "tracer", "of raw", "of smallest");
  for (const RawThroughput& t : out) {
    const RawThroughput& first = out[t.threads == out.front().threads ? 0 : 1];
    std::printf("%-16s %9zu %7u %11llu %11llu %9.2f %9.2f %7.1f%% %11.1f%%\n", t.scene.c_str(),
                t.patches, t.threads, static_cast<unsigned long long>(t.rays),
                static_cast<unsigned long long>(t.planned_rays), t.raw_rays_per_second / 1e6,
                t.runner_rays_per_second / 1e6, 100 * t.runner_over_raw,
                100 * t.runner_rays_per_second / first.runner_rays_per_second);
  }
  const std::string path = options.json_path == DefaultJsonPath("solver_bench")
                               ? DefaultJsonPath("solver_bench_buildings")
                               : options.json_path;
  WriteJson(path, RawBuildingsJson(machine, out, total.Seconds(), ReadLoadAverage()));
  std::printf("wrote %s in %.0f s\n", path.c_str(), total.Seconds());
  return 0;
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

  if (!options.raw_buildings.empty()) return RunRawBuildings(options, report.machine);
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
