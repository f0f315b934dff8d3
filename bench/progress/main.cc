// progress_bench: does the ETA `radfarm render` shows tell the truth? Solves every shipped job
// file (scenes/*.toml) and the procedural building (`radfarm building`, 2x2 and 4x4 rooms), and
// at every round and every tenth of the final gather records the ETA shown against the time that
// was really left (bench/progress/eta_trace.h). Prints a table per job and writes
// bench/results/progress_bench.json for scripts/bench-report (docs/BENCHMARKS.md).
//
//   progress_bench [--threads N] [--quick] [--only NAME] [--json PATH]
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_json.h"
#include "bench/bench_scene.h"
#include "bench/machine_info.h"
#include "bench/progress/eta_trace.h"
#include "bench/stopwatch.h"

namespace radfarm::bench {
namespace {

// Points with less time left than this are not judged: a tenth of a second late is no lie.
constexpr double kJudgedSeconds = 1.0;

struct Options {
  unsigned threads = 2;
  bool quick = false;
  std::string only;
  std::string json = DefaultJsonPath("progress_bench");
};

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--threads") {
      o.threads = unsigned(std::stoul(next()));
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--only") {
      o.only = next();
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "progress_bench [--threads N] [--quick] [--only NAME] [--json PATH]\n"
          "  The ETA render shows at every round against the time really left, for every\n"
          "  scenes/*.toml and the building at 2x2 and 4x4 rooms (--quick: the Cornell box and\n"
          "  the 2x2 building). Writes bench/results/progress_bench.json unless --json says "
          "where.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  return o;
}

// `radfarm building --rooms NxN` written to `dir`; its job file.
std::string WriteBuilding(int rooms, const std::string& dir, const std::string& name) {
  scenegen::BuildingParams params;
  params.rooms_x = params.rooms_z = rooms;
  return WriteBuildingJob(params, 0.25, dir, name);  // radfarm building's default patch size
}

// |predicted / actual - 1| of the judged points; a "?" counts as infinitely wrong.
std::vector<double> Errors(const EtaTrace& t) {
  std::vector<double> errors;
  for (const EtaPoint& p : t.points) {
    if (p.actual_left < kJudgedSeconds) continue;
    errors.push_back(p.predicted_left < 0 ? INFINITY
                                          : std::fabs(p.predicted_left / p.actual_left - 1));
  }
  return errors;
}

nlohmann::json TraceJson(const EtaTrace& t) {
  nlohmann::json points = nlohmann::json::array();
  for (const EtaPoint& p : t.points) {
    points.push_back({{"round", p.round},
                      {"in_gather", p.in_gather},
                      {"seconds", p.seconds},
                      {"predicted_left",
                       p.predicted_left < 0 ? nlohmann::json() : nlohmann::json(p.predicted_left)},
                      {"actual_left", p.actual_left},
                      {"fraction", p.fraction}});
  }
  const std::vector<double> errors = Errors(t);
  return {{"scene", t.scene},
          {"patches", t.patches},
          {"threads", t.threads},
          {"rays", t.rays},
          {"seconds", t.seconds},
          {"gather_ray_cost_probed", t.gather_ray_cost_probed},
          {"gather_ray_cost_seen", t.gather_ray_cost_seen},
          {"judged_points", errors.size()},
          {"max_error", errors.empty()
                            ? nlohmann::json()
                            : nlohmann::json(*std::max_element(errors.begin(), errors.end()))},
          {"median_error", errors.empty() ? nlohmann::json() : nlohmann::json(Median(errors))},
          {"points", points}};
}

void PrintTrace(const EtaTrace& t) {
  std::printf("%s: %llu patches, %llu rays, %.1f s on %u threads\n", t.scene.c_str(),
              static_cast<unsigned long long>(t.patches), static_cast<unsigned long long>(t.rays),
              t.seconds, t.threads);
  std::printf("  a gather ray's cost over a shooting ray's: %.2f probed, %.2f seen\n",
              t.gather_ray_cost_probed, t.gather_ray_cost_seen);
  std::printf("  %5s %7s %9s %11s %10s %7s %6s\n", "round", "gather", "at s", "ETA s", "left s",
              "error", "bar");
  for (const EtaPoint& p : t.points) {
    char eta[32] = "?", error[32] = "-";
    if (p.predicted_left >= 0) {
      std::snprintf(eta, sizeof eta, "%.2f", p.predicted_left);
      if (p.actual_left >= kJudgedSeconds) {
        std::snprintf(error, sizeof error, "%+.0f%%", 100 * (p.predicted_left / p.actual_left - 1));
      }
    }
    std::printf("  %5u %7s %9.2f %11s %10.2f %7s %5.0f%%\n", p.round, p.in_gather ? "yes" : "",
                p.seconds, eta, p.actual_left, error, 100 * p.fraction);
  }
  const std::vector<double> errors = Errors(t);
  if (!errors.empty()) {
    std::printf("  judged %zu points (>= %.0f s left): max error %.0f%%, median %.0f%%\n\n",
                errors.size(), kJudgedSeconds,
                100 * *std::max_element(errors.begin(), errors.end()), 100 * Median(errors));
  }
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  const Stopwatch total;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("radfarm-progress-bench-" + std::to_string(::getpid()));
  struct RemoveDir {
    std::filesystem::path dir;
    ~RemoveDir() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } remove{dir};

  std::vector<std::pair<std::string, std::string>> jobs;  // name, job file
  const std::string scenes = RADFARM_SOURCE_DIR "/scenes/";
  for (const char* scene :
       {"cornell-box", "cornell-box-far", "cornell-box-adaptive", "hard-shadow", "seed-room"}) {
    if (o.quick && std::string(scene) != "cornell-box") continue;
    jobs.emplace_back(scene, scenes + scene + ".toml");
  }
  for (int rooms : {2, 4}) {
    if (o.quick && rooms > 2) continue;
    const std::string name = "building-" + std::to_string(rooms) + "x" + std::to_string(rooms);
    jobs.emplace_back(name, WriteBuilding(rooms, dir.string(), name));
  }

  nlohmann::json runs = nlohmann::json::array();
  for (const auto& [name, path] : jobs) {
    if (!o.only.empty() && name != o.only) continue;
    const EtaTrace trace = TraceJob(name, path, o.threads);
    PrintTrace(trace);
    runs.push_back(TraceJson(trace));
  }
  nlohmann::json out{{"machine", MachineJson(machine)},
                     {"quick", o.quick},
                     {"judged_seconds", kJudgedSeconds},
                     {"runs", runs},
                     {"total_seconds", total.Seconds()}};
  out["load_average_end"] = ReadLoadAverage();
  WriteJson(o.json, out);
  std::printf("wrote %s\n", o.json.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "progress_bench: %s\n", e.what());
    return 1;
  }
}
