#include "bench/scaling/scaling_runs.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "bench/memory/peak_rss.h"
#include "scenegen/building_params.h"
#include "testing/loopback_farm.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

using Clock = std::chrono::steady_clock;

// testing::ReadFile gives "" for a file it cannot read.
nlohmann::json ReadJsonFile(const std::string& path) {
  const std::string text = testing::ReadFile(path);
  if (text.empty()) throw std::runtime_error(path + ": cannot read");
  return nlohmann::json::parse(text);
}

// The number after `marker` in `text` ("read and meshed in 1.0 s"), or 0 when absent.
double NumberAfter(const std::string& text, const std::string& marker) {
  const size_t at = text.find(marker);
  return at == std::string::npos ? 0 : std::strtod(text.c_str() + at + marker.size(), nullptr);
}

uint64_t RoomsOf(const std::string& rooms) {
  const Result<std::pair<int, int>> counts = scenegen::ParseRoomCounts(rooms);
  if (!counts) throw std::runtime_error("--rooms: " + counts.error());
  return uint64_t(counts->first) * uint64_t(counts->second);
}

// Seconds since the epoch of a log line's timestamp ("2026-12-03T17:44:53.488Z ..."), or -1.
double LineTime(const std::string& line) {
  std::tm t{};
  int ms = 0;
  if (std::sscanf(line.c_str(), "%d-%d-%dT%d:%d:%d.%dZ", &t.tm_year, &t.tm_mon, &t.tm_mday,
                  &t.tm_hour, &t.tm_min, &t.tm_sec, &ms) != 7) {
    return -1;
  }
  t.tm_year -= 1900;
  t.tm_mon -= 1;
  return static_cast<double>(timegm(&t)) + ms / 1000.0;
}

}  // namespace

AgentStart ReadAgentStart(const std::string& log_text) {
  double lease = -1, ready = -1, result = -1;
  std::istringstream lines(log_text);
  for (std::string line; std::getline(lines, line);) {
    const double t = LineTime(line);
    if (t < 0) continue;
    if (lease < 0 && line.find("agent: received ") != std::string::npos &&
        line.find(" batches of round ") != std::string::npos) {
      lease = t;
    } else if (lease >= 0 && ready < 0 && line.find(": ready, ") != std::string::npos) {
      ready = t;
    } else if (lease >= 0 && result < 0 && line.find(" results sent to ") != std::string::npos) {
      result = t;
    }
  }
  // The log's resolution is a millisecond.
  const auto seconds = [](double from, double to) { return std::round((to - from) * 1000) / 1000; };
  AgentStart start;
  if (lease >= 0 && ready >= 0) start.scene_ready_seconds = seconds(lease, ready);
  if (lease >= 0 && result >= 0) start.first_result_seconds = seconds(lease, result);
  return start;
}

BuildingJob WriteBuildingJob(const std::string& rooms, uint64_t rays_per_room,
                             const std::string& dir) {
  BuildingJob job{rooms, dir + "/building.toml", RoomsOf(rooms) * rays_per_room};
  std::filesystem::create_directories(dir);
  const MeasuredRun run =
      RunMeasured({RADFARM_CLI_PATH, "building", "--rooms", rooms, "--patch-size", "0",
                   "--refine-tolerance", "0", "--out", dir},
                  dir + "/building.log");
  if (run.exit_code != 0) throw std::runtime_error("radfarm building failed: see " + dir);
  return job;
}

RenderFigures MeasureRender(const BuildingJob& job, const std::string& dir) {
  const std::string out = dir + "/render";
  const std::string log = dir + "/render.log";
  const MeasuredRun run = RunMeasured({RADFARM_CLI_PATH, "render", job.toml, "--out", out, "--rays",
                                       std::to_string(job.rays), "--threads", "2"},
                                      log);
  if (run.exit_code != 0) throw std::runtime_error("render failed: see " + log);
  const nlohmann::json stats = ReadJsonFile(out + "/stats.json");
  RenderFigures r;
  r.patches = stats.at("patches").get<uint64_t>();
  r.rays = stats.at("rays").get<uint64_t>();
  r.wall_seconds = run.seconds;
  r.mesh_seconds = NumberAfter(testing::ReadFile(log), "read and meshed in ");
  r.solve_seconds = stats.at("seconds").get<double>();
  r.display_seconds = stats.value("display_seconds", 0.0);
  r.rays_per_second = stats.at("rays_per_second").get<double>();
  r.peak_rss_bytes = run.peak_rss_bytes;
  r.patches_csv = out + "/patches.csv";
  return r;
}

FarmFigures MeasureFarm(const BuildingJob& job, unsigned agents, const RenderFigures& render,
                        const std::string& dir) {
  const std::string farm_dir = dir + "/farm";
  std::filesystem::create_directories(farm_dir);
  testing::LoopbackFarm farm({RADFARMD_PATH, RADFARM_AGENT_PATH, RADFARM_CLI_PATH}, farm_dir);
  const pid_t master = farm.StartMaster({"--log-level", "info"}).pid();
  if (farm.master_address().empty()) throw std::runtime_error("radfarmd: " + farm.MasterLog());
  std::vector<pid_t> agent_pids;
  for (unsigned k = 0; k < agents; ++k) {
    // Debug: the lease frames and results sent, for ReadAgentStart (a few lines a lease frame).
    agent_pids.push_back(
        farm.StartAgent("a" + std::to_string(k), 1, {"--log-level", "debug"}).pid());
  }
  if (!farm.WaitForAgents(agents, std::chrono::seconds(60))) {
    throw std::runtime_error("the agents did not connect");
  }
  std::string error;
  const Clock::time_point submitted = Clock::now();
  const int64_t id = farm.Submit(job.toml, {"--rays", std::to_string(job.rays)}, &error);
  if (id < 0) throw std::runtime_error("submit failed: " + error);
  const nlohmann::json done = farm.WaitForJob(id, testing::IsFinished, std::chrono::minutes(120),
                                              std::chrono::milliseconds(100));
  FarmFigures f;
  f.job_seconds = std::chrono::duration<double>(Clock::now() - submitted).count();
  if (done.is_null() || done.value("state", "") != "done") {
    throw std::runtime_error("farm job did not finish: " + done.dump());
  }
  f.master_peak_rss_bytes = PeakRssOf(master);
  for (pid_t pid : agent_pids)
    f.agent_peak_rss_bytes = std::max(f.agent_peak_rss_bytes, PeakRssOf(pid));
  const std::string out = farm_dir + "/out";
  if (farm.Fetch(id, out).exit_code != 0) throw std::runtime_error("fetch failed");
  const nlohmann::json stats = ReadJsonFile(out + "/stats.json");
  f.solve_seconds = stats.at("seconds").get<double>();
  f.rays_per_second = stats.at("rays_per_second").get<double>();
  const std::string farm_patches = testing::ReadFile(out + "/patches.csv");
  f.same_as_render = !farm_patches.empty() && farm_patches == testing::ReadFile(render.patches_csv);
  for (unsigned k = 0; k < agents; ++k) {
    const AgentStart start =
        ReadAgentStart(testing::ReadFile(farm_dir + "/agent-a" + std::to_string(k) + ".log"));
    f.agent_scene_ready_seconds = std::max(f.agent_scene_ready_seconds, start.scene_ready_seconds);
    f.agent_first_result_seconds =
        std::max(f.agent_first_result_seconds, start.first_result_seconds);
  }
  return f;
}

}  // namespace radfarm::bench
