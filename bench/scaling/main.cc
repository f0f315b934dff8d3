// scaling_bench: time, peak memory and rays/s against patch count, from 10^3 to 10^6 patches, for
// `radfarm render` and for a loopback farm, on the procedural office building (scenegen/) with the
// automatic patch size: more rooms, more patches at the same density. Every size gets the same
// rays per room, so the rays per patch stay about constant and what grows is the scene.
// Prints a table and the log-log slopes (how each figure grows with the patches) and writes
// bench/results/scaling_bench.json, which scripts/bench-report draws in docs/SCALING.md.
//
//   scaling_bench [--rooms 1x1,2x2,...] [--rays-per-room N] [--agents N] [--no-farm] [--json PATH]
//                 [--keep DIR]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/scaling/scaling_runs.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

struct Options {
  std::vector<std::string> rooms = {"1x1", "2x2", "4x4", "6x6", "12x12", "18x18"};
  uint64_t rays_per_room = 400000;
  unsigned agents = 2;
  bool farm = true;
  std::string json = DefaultJsonPath("scaling_bench");
  std::string keep;  // write the scenes, outputs and logs here instead of a temporary directory
};

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--rooms") {
      o.rooms.clear();
      std::stringstream list(next());
      for (std::string item; std::getline(list, item, ',');) o.rooms.push_back(item);
    } else if (a == "--rays-per-room") {
      o.rays_per_room = std::stoull(next());
    } else if (a == "--agents") {
      o.agents = static_cast<unsigned>(std::stoul(next()));
    } else if (a == "--no-farm") {
      o.farm = false;
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "--keep") {
      o.keep = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "scaling_bench [--rooms LIST] [--rays-per-room N] [--agents N] [--no-farm]\n"
          "              [--json PATH] [--keep DIR]\n"
          "  Time, peak memory and rays/s against patch count for radfarm render (2 threads) and\n"
          "  a\n"
          "  loopback farm (radfarmd and N agents of 1 thread, default 2), on the procedural\n"
          "  building with rooms AxB from LIST (default 1x1,2x2,4x4,6x6,12x12,18x18: about 3,000\n"
          "  to 920,000 patches), each solved to N rays per room (default 400000). Writes\n"
          "  bench/results/scaling_bench.json unless --json says where. --keep DIR: write the\n"
          "  scenes, outputs and the daemons' logs under DIR and leave them there.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  if (o.rooms.empty()) throw std::runtime_error("--rooms: no size given");
  if (o.rays_per_room == 0) throw std::runtime_error("--rays-per-room: must be positive");
  if (o.farm && o.agents == 0) throw std::runtime_error("--agents: must be positive");
  return o;
}

// The least-squares slope of log(y) against log(patches) over the runs with at least 10^4
// patches (below that fixed costs dominate): 1 is linear growth, 0 none.
double LogLogSlope(const nlohmann::json& runs, const char* key) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const nlohmann::json& run : runs) {
    const double patches = run.at("patches").get<double>();
    if (patches < 1e4 || !run.contains(key) || run.at(key).get<double>() <= 0) continue;
    const double x = std::log(patches), y = std::log(run.at(key).get<double>());
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : 0;
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  std::optional<testing::TempDir> temp;
  if (o.keep.empty()) temp.emplace("scaling_bench");
  const std::string root = o.keep.empty() ? temp->path() : o.keep;
  nlohmann::json runs = nlohmann::json::array();
  std::printf("%7s %9s %11s | %8s %7s %8s %8s %8s %9s | %8s %8s %9s %9s %8s %5s\n", "rooms",
              "patches", "rays", "wall s", "mesh s", "solve s", "disp s", "Mrays/s", "peak MB",
              "job s", "Mrays/s", "master MB", "agent MB", "wall %", "same");
  for (const std::string& rooms : o.rooms) {
    const std::string here = root + "/" + rooms;
    const BuildingJob job = WriteBuildingJob(rooms, o.rays_per_room, here);
    const RenderFigures r = MeasureRender(job, here);
    nlohmann::json run = {{"rooms", rooms},
                          {"patches", r.patches},
                          {"rays", r.rays},
                          {"render_wall_seconds", r.wall_seconds},
                          {"render_mesh_seconds", r.mesh_seconds},
                          {"render_solve_seconds", r.solve_seconds},
                          {"render_display_seconds", r.display_seconds},
                          {"render_rays_per_second", r.rays_per_second},
                          {"render_peak_rss_bytes", r.peak_rss_bytes}};
    std::printf("%7s %9llu %11llu | %8.1f %7.1f %8.1f %8.1f %8.2f %9.1f |", rooms.c_str(),
                static_cast<unsigned long long>(r.patches), static_cast<unsigned long long>(r.rays),
                r.wall_seconds, r.mesh_seconds, r.solve_seconds, r.display_seconds,
                r.rays_per_second / 1e6, r.peak_rss_bytes / kMiB);
    if (o.farm) {
      const FarmFigures f = MeasureFarm(job, o.agents, r, here);
      run.update({{"farm_job_seconds", f.job_seconds},
                  {"farm_solve_seconds", f.solve_seconds},
                  {"farm_rays_per_second", f.rays_per_second},
                  {"master_peak_rss_bytes", f.master_peak_rss_bytes},
                  {"agent_peak_rss_bytes", f.agent_peak_rss_bytes},
                  {"agent_scene_ready_seconds", f.agent_scene_ready_seconds},
                  {"agent_first_result_seconds", f.agent_first_result_seconds},
                  {"farm_same_as_render", f.same_as_render}});
      // The farm's job against render's solve and meshing (the display is fetch's, not timed).
      const double embedded = r.mesh_seconds + r.solve_seconds;
      std::printf(" %8.1f %8.2f %9.1f %9.1f %7.1f%% %5s\n", f.job_seconds, f.rays_per_second / 1e6,
                  f.master_peak_rss_bytes / kMiB, f.agent_peak_rss_bytes / kMiB,
                  100 * embedded / f.job_seconds, f.same_as_render ? "yes" : "NO");
      std::printf(
          "%7s   first lease to scene ready %.2f s, to first result %.2f s "
          "(slowest agent)\n",
          "", f.agent_scene_ready_seconds, f.agent_first_result_seconds);
    } else {
      std::printf("\n");
    }
    std::fflush(stdout);
    runs.push_back(std::move(run));
  }
  nlohmann::json slopes = nlohmann::json::object();
  for (const char* key : {"render_wall_seconds", "render_mesh_seconds", "render_solve_seconds",
                          "render_display_seconds", "render_rays_per_second",
                          "render_peak_rss_bytes", "farm_job_seconds", "farm_rays_per_second",
                          "master_peak_rss_bytes", "agent_peak_rss_bytes"}) {
    if (!runs.front().contains(key)) continue;
    slopes[key] = LogLogSlope(runs, key);
  }
  std::printf("\nlog-log slopes against patches (runs of 10^4 patches and more; 1 = linear):\n");
  for (const auto& [key, value] : slopes.items()) {
    std::printf("  %-24s %6.2f\n", key.c_str(), value.get<double>());
  }
  WriteJson(o.json, {{"machine", MachineJson(machine)},
                     {"scene", "radfarm building --rooms AxB --patch-size 0"},
                     {"rays_per_room", o.rays_per_room},
                     {"agents", o.farm ? o.agents : 0},
                     {"runs", runs},
                     {"log_log_slopes", slopes}});
  std::printf("wrote %s\n", o.json.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scaling_bench: %s\n", e.what());
    return 1;
  }
}
