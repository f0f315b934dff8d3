#include "bench/farm/real_compute.h"

#include <stdlib.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "bench/stopwatch.h"
#include "testing/child_process.h"
#include "testing/temp_dir.h"

namespace radfarm::bench {
namespace {

using testing::ReadFile;

nlohmann::json ReadStats(const std::string& dir) {
  nlohmann::json stats = nlohmann::json::parse(ReadFile(dir + "/stats.json"), nullptr, false);
  if (!stats.is_object()) throw std::runtime_error("no stats.json in " + dir);
  return stats;
}

void AddSample(RealComputeSetup& setup, const nlohmann::json& stats, double wall) {
  const double seconds = stats.at("seconds").get<double>();
  setup.rays = stats.at("rays").get<uint64_t>();
  setup.rounds = stats.at("rounds").get<uint32_t>();
  setup.solve_seconds.push_back(seconds);
  setup.rays_per_second.push_back(seconds > 0 ? double(setup.rays) / seconds : 0);
  setup.wall_seconds.push_back(wall);
}

// CPU seconds of this process's children that have ended (and been waited for).
double EndedChildrenCpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// `radfarm render JOB --out DIR --threads 2 -q`; returns patches.csv.
std::string RunEmbedded(const RealComputeConfig& config, const std::string& out,
                        RealComputeSetup& setup) {
  std::vector<std::string> args = {
      config.programs.cli, "render", config.job_file, "--out", out, "--threads", "2", "-q"};
  args.insert(args.end(), config.overrides.begin(), config.overrides.end());
  const double cpu_before = EndedChildrenCpuSeconds();
  const Stopwatch wall;
  const testing::CommandResult r = testing::RunCommand(args);
  const double seconds = wall.Seconds();
  if (r.exit_code != 0) throw std::runtime_error("radfarm render failed: " + r.err);
  AddSample(setup, ReadStats(out), seconds);
  setup.cpu_seconds.push_back(EndedChildrenCpuSeconds() - cpu_before);
  return ReadFile(out + "/patches.csv");
}

// A fresh farm of `agents` agents with `threads` threads each; submits, waits, fetches.
// `authenticate_only`: master and agents seal frames without encrypting them
// (RADFARM_WIRE_SEAL=authenticate-only, protocol/frame_seal.h), to measure what encryption costs.
void RunFarm(const RealComputeConfig& config, const std::string& dir, int agents, unsigned threads,
             const std::string& reference_patches, RealComputeSetup& setup,
             bool authenticate_only = false) {
  std::filesystem::create_directories(dir);
  LoopbackFarm farm(config.programs, dir);
  // The children inherit it; this process seals nothing.
  if (authenticate_only) ::setenv("RADFARM_WIRE_SEAL", "authenticate-only", 1);
  StartMaster(farm);
  std::vector<pid_t> agent_pids;
  for (int a = 0; a < agents; ++a) {
    agent_pids.push_back(farm.StartAgent("agent" + std::to_string(a), threads).pid());
  }
  ::unsetenv("RADFARM_WIRE_SEAL");
  WaitForAgents(farm, agents);
  const auto cpu_now = [&] {
    std::pair<double, double> cpu{testing::ProcessCpuSeconds(farm.master()->pid()).value_or(0), 0};
    for (pid_t pid : agent_pids) cpu.second += testing::ProcessCpuSeconds(pid).value_or(0);
    return cpu;
  };
  const auto [master_before, agents_before] = cpu_now();
  // submit takes render's overrides, so both solve the same job.
  const int64_t id = Submit(farm, config.job_file, config.overrides);
  const nlohmann::json job = WaitDone(farm, id, std::chrono::seconds(900));
  const auto [master_after, agents_after] = cpu_now();
  setup.cpu_seconds.push_back(master_after - master_before);
  setup.agents_cpu_seconds.push_back(agents_after - agents_before);
  const std::string out = dir + "/fetched";
  Fetch(farm, id, out);
  const double wall = 1e-3 * double(job.at("finished_at_ms").get<int64_t>() -
                                    job.at("started_at_ms").get<int64_t>());
  AddSample(setup, ReadStats(out), wall);
  setup.patches_identical =
      setup.patches_identical && ReadFile(out + "/patches.csv") == reference_patches;
}

}  // namespace

RealComputeResult RunRealCompute(const RealComputeConfig& config) {
  RealComputeResult result;
  result.job = std::filesystem::path(config.job_file).filename().string();
  for (const std::string& o : config.overrides) result.job += " " + o;
  const auto setup = [](std::string name, std::string detail) {
    RealComputeSetup s;
    s.name = std::move(name);
    s.detail = std::move(detail);
    return s;
  };
  result.setups = {
      setup("embedded", "`radfarm render --threads 2`"),
      setup("farm 1 agent x 2 threads", "radfarmd + 1 `radfarm-agent --threads 2`"),
      setup("farm 2 agents x 1 thread", "radfarmd + 2 `radfarm-agent --threads 1`"),
      setup("farm 1 agent x 2 threads, frames not encrypted",
            "as farm 1 x 2, `RADFARM_WIRE_SEAL=authenticate-only` (frames authenticated, in "
            "clear)"),
  };
  for (int rep = 0; rep < config.repetitions; ++rep) {
    const std::string base = config.work_dir + "/real-" + std::to_string(rep);
    std::filesystem::create_directories(base);
    const std::string reference = RunEmbedded(config, base + "/render", result.setups[0]);
    std::printf("  rep %d: embedded %.2f Mrays/s", rep + 1,
                result.setups[0].rays_per_second.back() / 1e6);
    // Encrypted and clear back to back, in alternating order, so that a change in the machine's
    // load between them weighs on both alike (their ratio is the cost of encryption).
    for (const bool clear : {rep % 2 == 1, rep % 2 == 0}) {
      RunFarm(config, base + (clear ? "/farm-1x2-clear" : "/farm-1x2"), 1, 2, reference,
              result.setups[clear ? 3 : 1], clear);
    }
    std::printf(", farm 1x2 %.2f, not encrypted %.2f",
                result.setups[1].rays_per_second.back() / 1e6,
                result.setups[3].rays_per_second.back() / 1e6);
    RunFarm(config, base + "/farm-2x1", 2, 1, reference, result.setups[2]);
    std::printf(", farm 2x1 %.2f Mrays/s\n", result.setups[2].rays_per_second.back() / 1e6);
    std::fflush(stdout);
    std::filesystem::remove_all(base);
  }
  return result;
}

}  // namespace radfarm::bench
