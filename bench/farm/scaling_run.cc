#include "bench/farm/scaling_run.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "farmsim/agent_swarm.h"
#include "farmsim/idle_split.h"
#include "testing/child_process.h"

namespace radfarm::bench {
namespace {

constexpr double kReflectance = 0.9;  // furnace.mtl's Kd
constexpr double kPatchSize = 0.125;  // 6 faces x 8 x 8 = 384 patches

std::string WriteJobFile(const std::string& dir, const std::string& scenes_dir,
                         const ScalingCase& c) {
  // Converged once the unshot power is at or below 0.9^rounds: exactly after `rounds` rounds.
  const double tolerance = std::pow(kReflectance, c.rounds) * 1.0005;
  const std::string path = dir + "/furnace-sim.toml";
  std::ofstream out(path);
  out << "# farm_bench's simulated-agent job: see bench/farm/scaling_run.h\n"
      << "scene = \"" << std::filesystem::absolute(scenes_dir + "/furnace.obj").string() << "\"\n"
      << "[mesh]\npatch_size = " << kPatchSize << "\n"
      << "[solver]\nsampler = \"sobol\"\nseed = 1\n"
      << "tolerance = " << tolerance << "\n"
      << "shot_rays = " << c.shot_rays << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

}  // namespace

uint64_t RaiseOpenFileLimit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return 0;
  if (limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    setrlimit(RLIMIT_NOFILE, &limit);
    getrlimit(RLIMIT_NOFILE, &limit);
  }
  return limit.rlim_cur;
}

ScalingSample RunScalingCase(const FarmPrograms& programs, const std::string& scenes_dir,
                             const std::string& work_dir, const ScalingCase& c) {
  std::filesystem::create_directories(work_dir);
  const std::string job_file = WriteJobFile(work_dir, scenes_dir, c);
  LoopbackFarm farm(programs, work_dir);
  // Simulated results are not physics (simulated_result.h): exact validation would convict every
  // simulated agent, so it is off here; bench/verify measures its cost with real agents.
  std::vector<std::string> flags = c.master_flags;
  flags.insert(flags.end(), {"--verify-fraction", "0"});
  // The swarm connects every agent within milliseconds, as no office does; a simulated agent the
  // door evicts does not come back (a real one reconnects after its backoff). So the quota of
  // connections still in their handshake holds them all.
  flags.insert(flags.end(),
               {"--max-unauthenticated", std::to_string(std::max<size_t>(64, c.agents + 16))});
  StartMaster(farm, flags);
  const pid_t master_pid = farm.master()->pid();
  const double master_cpu_start = testing::ProcessCpuSeconds(master_pid).value_or(0);
  const double loop_cpu_start = testing::MainThreadCpuSeconds(master_pid).value_or(0);

  sim::SwarmConfig config;
  config.master_address = farm.master_address();
  config.secret_hex = farm.secret_hex();
  config.agents = c.agents;
  config.agent.rays_per_second = c.rays_per_second;
  config.agent.latency_seconds = c.latency_ms / 1000;
  sim::AgentSwarm swarm(config);
  swarm.Start();
  const double master_cpu_connected = testing::ProcessCpuSeconds(master_pid).value_or(0);
  const double loop_cpu_connected = testing::MainThreadCpuSeconds(master_pid).value_or(0);
  const int64_t id = Submit(farm, job_file);
  const sim::SwarmReport report = swarm.Finish(std::chrono::seconds(600));
  const nlohmann::json job = WaitDone(farm, id, std::chrono::seconds(60));
  const double master_cpu_end = testing::ProcessCpuSeconds(master_pid).value_or(0);
  const double loop_cpu_end = testing::MainThreadCpuSeconds(master_pid).value_or(0);

  ScalingSample s;
  s.job_rays = job.at("rays").get<uint64_t>();
  s.rounds = job.at("round").get<uint32_t>();
  s.wall_seconds = report.job_end - report.job_start;
  s.master_cpu_seconds = master_cpu_end - master_cpu_start;
  s.master_connect_cpu_seconds = master_cpu_connected - master_cpu_start;
  s.master_loop_cpu_seconds = loop_cpu_end - loop_cpu_start;
  s.master_loop_connect_cpu_seconds = loop_cpu_connected - loop_cpu_start;
  s.swarm_cpu_seconds = report.cpu_seconds;
  s.mean_lateness = report.mean_lateness;
  s.max_lateness = report.max_lateness;
  s.connect_seconds = report.connect_seconds;
  s.agent_errors = report.errors.size();
  if (!report.errors.empty()) s.first_error = report.errors.front();
  double busy = 0;
  s.utilisation_min = 1;
  for (const sim::SimAgentStats& a : report.agents) {
    s.batches += a.batches;
    s.computed_rays += a.rays;
    s.bytes_sent += double(a.bytes_sent);
    s.bytes_received += double(a.bytes_received);
    s.scene_bytes += double(a.scene_bytes_received);
    s.frames += a.frames_sent + a.frames_received;
    const double u = s.wall_seconds > 0 ? a.busy_seconds / s.wall_seconds : 0;
    busy += u;
    s.utilisation_min = std::min(s.utilisation_min, u);
  }
  s.idle = sim::SplitIdleTime(report, c.agents, s.wall_seconds);
  s.utilisation_mean = report.agents.empty() ? 0 : busy / double(report.agents.size());
  s.efficiency = s.wall_seconds > 0 ? (double(s.job_rays) / c.rays_per_second) /
                                          (double(c.agents) * s.wall_seconds)
                                    : 0;
  return s;
}

}  // namespace radfarm::bench
