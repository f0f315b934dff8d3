// rebake_bench: a re-bake (`radfarm render --from`) against the full bake of the same changed
// scene, in the furnished room of eight lamps (bench/rebake/furnished_room.h): the CPU seconds and
// rays of each, and each one's error against the path-traced reference at the same patch centres.
// Prints a table and writes bench/results/rebake_bench.json.
//
//   rebake_bench [--threads N] [--patch-size M] [--stride K] [--relative-error R] [--out FILE]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "base/cpu_clock.h"
#include "bench/bench_json.h"
#include "bench/rebake/furnished_room.h"
#include "mesh/patch_mesh.h"
#include "solve/local_solve.h"
#include "solve/previous_solve.h"

namespace radfarm::bench {
namespace {

struct Options {
  unsigned threads = 2;
  double patch_size = 0.25;
  uint32_t stride = 17;
  double relative_error = 0.005;
  std::string out = DefaultJsonPath("rebake_bench");
};

struct Case {
  const char* name;
  RoomChange after;
};

struct Run {
  SolveResult solution;
  PatchScene scene;
  double cpu_seconds = 0;
  double wall_seconds = 0;
};

Run SolveRoom(const Options& o, const RoomChange& change, const PreviousPatchValues* previous) {
  Result<PatchMesh> mesh =
      PatchMesh::Build(FurnishedRoom(change), MeshSettings{.patch_size = o.patch_size}, nullptr);
  if (!mesh) throw std::runtime_error(mesh.error());
  SolverSettings settings{.gather_rays = kDefaultGatherRays};
  settings.threads = o.threads;
  RefiningHooks hooks;
  if (previous != nullptr) {
    hooks.previous = previous;
    hooks.start = RebakeStart(*previous, o.threads);
  }
  LapClock clock;
  Result<RefiningSolveResult> solved =
      SolveRefining(std::move(*mesh), settings, RefineSettings{}, {}, hooks);
  const Spent spent = clock.Lap();
  if (!solved) throw std::runtime_error(solved.error());
  return {std::move(solved->solution), solved->mesh->patch_scene(), spent.cpu_seconds,
          spent.wall_seconds};
}

nlohmann::json RunJson(const Run& run, double error) {
  return {{"cpu_seconds", run.cpu_seconds},      {"wall_seconds", run.wall_seconds},
          {"rays", run.solution.stats.rays},     {"start_rays", run.solution.stats.start_rays},
          {"rounds", run.solution.stats.rounds}, {"rms_error", error}};
}

Options ParseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* v = i + 1 < argc ? argv[i + 1] : nullptr;
    if (v == nullptr) throw std::runtime_error("usage: " + a + " needs a value");
    if (a == "--threads")
      o.threads = unsigned(std::atoi(v));
    else if (a == "--patch-size")
      o.patch_size = std::atof(v);
    else if (a == "--stride")
      o.stride = uint32_t(std::atoi(v));
    else if (a == "--relative-error")
      o.relative_error = std::atof(v);
    else if (a == "--out")
      o.out = v;
    else
      throw std::runtime_error("unknown option " + a);
    ++i;
  }
  if (o.threads == 0 || o.patch_size <= 0 || o.stride == 0 || o.relative_error <= 0) {
    throw std::runtime_error("options out of range");
  }
  return o;
}

int Main(int argc, char** argv) {
  const Options o = ParseOptions(argc, argv);
  const std::vector<Case> cases = {
      {"dim one lamp of eight to 20 %", {.lamp0_scale = 0.2}},
      {"walls and table repainted", {.wall = {0.8, 0.75, 0.7}, .table = {0.1, 0.1, 0.1}}}};
  nlohmann::json json = {{"machine", MachineJson(ReadMachineInfo(argc, argv))},
                         {"threads", o.threads},
                         {"patch_size", o.patch_size},
                         {"reference_relative_error", o.relative_error}};
  std::printf("%-32s %8s %10s %10s %12s %12s %9s %9s\n", "change", "patches", "full cpu s",
              "rebake cpu", "full rays", "rebake rays", "full err", "rebake err");
  const Run before = SolveRoom(o, {}, nullptr);
  const PreviousPatchValues previous = PreviousValuesOf(before.scene, before.solution);
  for (const Case& c : cases) {
    const Run full = SolveRoom(o, c.after, nullptr);
    const Run rebake = SolveRoom(o, c.after, &previous);
    const PatchReference ref = TracePatchReference(FurnishedRoom(c.after), full.scene, o.stride,
                                                   o.relative_error, o.threads);
    const double full_error = RmsError(full.solution.radiosity, ref);
    const double rebake_error = RmsError(rebake.solution.radiosity, ref);
    const auto rays = [](const Run& r) {
      return static_cast<unsigned long long>(r.solution.stats.rays + r.solution.stats.start_rays);
    };
    std::printf("%-32s %8zu %10.2f %10.2f %12llu %12llu %8.2f%% %8.2f%%\n", c.name,
                full.scene.patches.size(), full.cpu_seconds, rebake.cpu_seconds, rays(full),
                rays(rebake), 100 * full_error, 100 * rebake_error);
    json["cases"].push_back({{"change", c.name},
                             {"patches", full.scene.patches.size()},
                             {"reference_points", ref.patches.size()},
                             {"full", RunJson(full, full_error)},
                             {"rebake", RunJson(rebake, rebake_error)}});
  }
  WriteJson(o.out, json);
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rebake_bench: %s\n", e.what());
    return 1;
  }
}
