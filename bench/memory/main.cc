// memory_bench: peak resident memory against patch count, for `radfarm render` and for a loopback
// farm (radfarmd and one radfarm-agent), on the Cornell box meshed ever finer. Each run stops at
// a ray budget: what grows with the patches is the mesh, the scene, the solver state and the ray
// caster, all built before the first ray, and the outputs after the last; a round's results are
// folded in as they arrive (core/round_reduction.h), so more rays do not raise the peak.
// The farm run also times an agent's start-up on a big job: the agent starts once the master has
// prepared the job (meshed it and packed its scene), and the clock runs until the master has
// accepted its first batch result: connection, handshake, the compressed scene's fetch,
// decompression, decoding, the BVH and the first batch.
// Prints a table and writes bench/results/memory_bench.json.
//
//   memory_bench [--sizes 25,12.5,5,2.5,1.6] [--rays 2000000] [--no-farm] [--json PATH]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_json.h"
#include "bench/machine_info.h"
#include "bench/memory/peak_rss.h"
#include "testing/loopback_farm.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

struct Options {
  std::vector<double> sizes = {25, 12.5, 5, 2.5, 1.6};
  uint64_t rays = 2000000;
  bool farm = true;
  std::string json = DefaultJsonPath("memory_bench");
};

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--sizes") {
      o.sizes.clear();
      std::stringstream list(next());
      for (std::string item; std::getline(list, item, ',');) o.sizes.push_back(std::stod(item));
    } else if (a == "--rays") {
      o.rays = std::stoull(next());
    } else if (a == "--no-farm") {
      o.farm = false;
    } else if (a == "--json") {
      o.json = next();
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "memory_bench [--sizes LIST] [--rays N] [--no-farm] [--json PATH]\n"
          "  Peak RSS of radfarm render and of a loopback farm against patch count (Cornell box,\n"
          "  --patch-size from LIST, default 25,12.5,5,2.5,1.6 mm; each run stops after N rays,\n"
          "  default 2000000). Writes bench/results/memory_bench.json unless --json says where.\n");
      std::exit(0);
    } else {
      throw std::runtime_error("unknown argument " + a + " (see --help)");
    }
  }
  if (o.sizes.empty()) throw std::runtime_error("--sizes: no patch size given");
  return o;
}

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  return nlohmann::json::parse(in);
}

std::string Fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string Format(double size) {
  std::ostringstream out;
  out << size;
  return out.str();
}

nlohmann::json MeasureRender(const Options& o, double size, const std::string& dir) {
  const std::string out = dir + "/render-" + Format(size);
  const MeasuredRun run = RunMeasured(
      {RADFARM_CLI_PATH, "render", RADFARM_SOURCE_DIR "/scenes/cornell-box.obj", "--out", out,
       "--patch-size", Format(size), "--rays", std::to_string(o.rays), "--threads", "2", "-q"},
      out + ".log");
  if (run.exit_code != 0) throw std::runtime_error("render failed: see " + out + ".log");
  const nlohmann::json stats = ReadJsonFile(out + "/stats.json");
  return {{"patch_size", size},
          {"patches", stats["patches"]},
          {"seconds", run.seconds},
          {"rays_per_second", stats["rays_per_second"]},
          {"peak_rss_bytes", run.peak_rss_bytes}};
}

// The master's line for a prepared job: "... (N bytes, M compressed)"; {N, M}, or {0, 0} before it.
std::pair<uint64_t, uint64_t> PreparedSceneSizes(const std::string& master_log) {
  const size_t end = master_log.find(" compressed)");
  if (end == std::string::npos) return {0, 0};
  const size_t open = master_log.rfind('(', end);
  unsigned long long bytes = 0, compressed = 0;
  if (std::sscanf(master_log.c_str() + open, "(%llu bytes, %llu", &bytes, &compressed) != 2) {
    throw std::runtime_error("cannot read the scene sizes in the master's log");
  }
  return {bytes, compressed};
}

uint64_t ResultsOfFirstAgent(const testing::LoopbackFarm& farm) {
  const nlohmann::json agents = farm.Agents();
  if (!agents.is_array() || agents.empty()) return 0;
  return agents.front().value("results", uint64_t{0});
}

nlohmann::json MeasureFarm(const Options& o, double size, const std::string& dir) {
  using Clock = std::chrono::steady_clock;
  const std::string farm_dir = dir + "/farm-" + Format(size);
  std::filesystem::create_directories(farm_dir);
  testing::LoopbackFarm farm({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, farm_dir);
  const pid_t master = farm.StartMaster({"--log-level", "info"}).pid();
  std::string error;
  const int64_t id =
      farm.Submit(RADFARM_SOURCE_DIR "/scenes/cornell-box.obj",
                  {"--patch-size", Format(size), "--rays", std::to_string(o.rays)}, &error);
  if (id < 0) throw std::runtime_error("submit failed: " + error);
  std::pair<uint64_t, uint64_t> scene{0, 0};
  const Clock::time_point give_up = Clock::now() + std::chrono::minutes(30);
  while ((scene = PreparedSceneSizes(farm.MasterLog())).first == 0) {
    if (Clock::now() > give_up) throw std::runtime_error("the master never prepared the job");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling, not synchronising
  }
  const Clock::time_point started = Clock::now();
  const pid_t agent = farm.StartAgent("a", 2).pid();
  while (ResultsOfFirstAgent(farm) == 0) {
    if (Clock::now() > give_up) throw std::runtime_error("the agent never returned a result");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double first_result_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  const nlohmann::json job =
      farm.WaitForJob(id, testing::IsFinished, std::chrono::minutes(30), std::chrono::seconds(1));
  if (job.is_null() || job.value("state", "") != "done") {
    throw std::runtime_error("farm job did not finish: " + job.dump());
  }
  return {{"patch_size", size},
          {"master_peak_rss_bytes", PeakRssOf(master)},
          {"agent_peak_rss_bytes", PeakRssOf(agent)},
          {"scene_bytes", scene.first},
          {"scene_compressed_bytes", scene.second},
          {"agent_start_to_first_result_seconds", first_result_seconds}};
}

// Bytes per patch above the smallest run's, over the largest run: the slope a fixed base does not
// hide.
double SlopePerPatch(const nlohmann::json& runs, const char* key) {
  const nlohmann::json& a = runs.front();
  const nlohmann::json& b = runs.back();
  const double patches = b["patches"].get<double>() - a["patches"].get<double>();
  return patches > 0 ? (b[key].get<double>() - a[key].get<double>()) / patches : 0;
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  const MachineInfo machine = ReadMachineInfo(argc, argv);
  testing::TempDir dir;
  nlohmann::json runs = nlohmann::json::array();
  std::printf("%10s %10s %9s %9s %12s %12s %10s %12s %10s\n", "patch size", "patches", "seconds",
              "Mrays/s", "render MB", "radfarmd MB", "agent MB", "scene MB/zstd", "1st res s");
  for (double size : o.sizes) {
    nlohmann::json run = MeasureRender(o, size, dir.path());
    if (o.farm) run.update(MeasureFarm(o, size, dir.path()));
    auto farm_figure = [&](const char* key, double scale) {
      return o.farm ? Fixed(run[key].get<double>() / scale, 1) : std::string("-");
    };
    const std::string scene = o.farm
                                  ? Fixed(run["scene_bytes"].get<double>() / kMiB, 1) + "/" +
                                        Fixed(run["scene_compressed_bytes"].get<double>() / kMiB, 1)
                                  : "-";
    std::printf(
        "%10s %10llu %9.2f %9.2f %12.1f %12s %10s %12s %10s\n", Format(size).c_str(),
        run["patches"].get<unsigned long long>(), run["seconds"].get<double>(),
        run["rays_per_second"].get<double>() / 1e6, run["peak_rss_bytes"].get<double>() / kMiB,
        farm_figure("master_peak_rss_bytes", kMiB).c_str(),
        farm_figure("agent_peak_rss_bytes", kMiB).c_str(), scene.c_str(),
        o.farm ? Fixed(run["agent_start_to_first_result_seconds"].get<double>(), 2).c_str() : "-");
    std::fflush(stdout);
    runs.push_back(std::move(run));
  }
  nlohmann::json slopes = {{"render", SlopePerPatch(runs, "peak_rss_bytes")}};
  if (o.farm) {
    slopes["radfarmd"] = SlopePerPatch(runs, "master_peak_rss_bytes");
    slopes["agent"] = SlopePerPatch(runs, "agent_peak_rss_bytes");
  }
  std::printf("\nbytes per patch above the smallest run:");
  for (const auto& [name, value] : slopes.items()) {
    std::printf(" %s %.0f", name.c_str(), value.get<double>());
  }
  std::printf("\n");
  WriteJson(o.json, {{"machine", MachineJson(machine)},
                     {"scene", "scenes/cornell-box.obj"},
                     {"rays", o.rays},
                     {"runs", runs},
                     {"bytes_per_patch_above_smallest", slopes}});
  std::printf("wrote %s\n", o.json.c_str());
  return 0;
}

}  // namespace
}  // namespace radfarm::bench

int main(int argc, char** argv) {
  try {
    return radfarm::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "memory_bench: %s\n", e.what());
    return 1;
  }
}
