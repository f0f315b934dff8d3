#include "bench/farm/scaling_suite.h"

#include <filesystem>
#include <string>
#include <vector>

namespace radfarm::bench {
namespace {

constexpr uint64_t kFurnacePatches = 384;
constexpr uint64_t kFirstRoundBatchRays = 4096;  // SchedulerOptions::default_batch_rays
// Every round goes to the simulated agents: one the master computed itself would be real compute
// outside the simulation (an efficiency above 100%), and these rows measure dispatch.
const std::vector<std::string> kEveryRoundLeased = {"--local-round-rays", "0"};

ScalingRow Scaling(size_t agents, double latency_ms, double round_seconds, int rounds) {
  ScalingCase c;
  c.agents = agents;
  c.rays_per_second = kOfficeRaysPerSecond;
  c.latency_ms = latency_ms;
  c.shot_rays = static_cast<uint64_t>(double(agents) * kOfficeRaysPerSecond * round_seconds);
  c.rounds = rounds;
  c.master_flags = kEveryRoundLeased;
  return {"scaling", c, {}};
}

ScalingRow Capacity(size_t agents, uint64_t batches_per_patch) {
  ScalingCase c;
  c.agents = agents;
  c.rays_per_second = kInstantRaysPerSecond;
  c.shot_rays = kFurnacePatches * batches_per_patch * kFirstRoundBatchRays;
  c.rounds = 1;
  c.master_flags = kEveryRoundLeased;
  return {"capacity", c, {}};
}

}  // namespace

SuitePlan MakeSuitePlan(bool quick) {
  SuitePlan plan;
  if (quick) {
    plan.repetitions = 1;
    plan.round_seconds = 0.75;
    for (size_t n : {10, 100}) {
      for (double latency : {0.0, 20.0}) plan.rows.push_back(Scaling(n, latency, 0.75, 2));
    }
    plan.rows.push_back(Capacity(100, 10));
    return plan;
  }
  plan.repetitions = 3;
  plan.round_seconds = 2;
  for (size_t n : {10, 100, 1000}) {
    for (double latency : {0.0, 20.0}) plan.rows.push_back(Scaling(n, latency, 2, 4));
  }
  for (size_t n : {100, 1000}) plan.rows.push_back(Capacity(n, 100));
  // As many batches an agent as the 100-agent case: the master at 1000 agents once every agent
  // is under way, without the round start that dominates 38 batches an agent.
  plan.rows.push_back(Capacity(1000, 1000));
  return plan;
}

void RunSuite(SuitePlan& plan, const FarmPrograms& programs, const std::string& scenes_dir,
              const std::string& work_dir) {
  int run = 0;
  for (int rep = 0; rep < plan.repetitions; ++rep) {
    for (ScalingRow& row : plan.rows) {
      const ScalingCase& c = row.config;
      const std::string dir = work_dir + "/sim-" + std::to_string(run++);
      const ScalingSample s = RunScalingCase(programs, scenes_dir, dir, c);
      std::filesystem::remove_all(dir);
      std::printf(
          "  %-8s N=%-4zu L=%2.0f ms: %7.2f s, %u rounds, %6.0f batches/s, efficiency %5.1f%%, "
          "utilisation %5.1f%% (min %5.1f%%), idle between/within rounds %4.1f%%/%4.1f%% "
          "(starts %4.1f%%, tails %4.1f%%), "
          "%.3f B/ray, master CPU %.2f s (%.2f s connecting, %.1f us/batch; loop thread %.2f s, "
          "%.2f s connecting), %.2f frames/batch, "
          "sim CPU %.2f s%s\n",
          row.group.c_str(), c.agents, c.latency_ms, s.wall_seconds, s.rounds,
          s.batches_per_second(), 100 * s.efficiency, 100 * s.utilisation_mean,
          100 * s.utilisation_min, 100 * s.idle.between_rounds, 100 * s.idle.within_rounds,
          100 * s.idle.round_starts, 100 * s.idle.round_tails, s.bytes_per_ray(),
          s.master_cpu_seconds, s.master_connect_cpu_seconds,
          s.batches ? 1e6 * s.master_cpu_seconds / double(s.batches) : 0.0,
          s.master_loop_cpu_seconds, s.master_loop_connect_cpu_seconds,
          s.batches ? double(s.frames) / double(s.batches) : 0.0, s.swarm_cpu_seconds,
          s.agent_errors ? (", agent errors: " + s.first_error).c_str() : "");
      std::fflush(stdout);
      row.samples.push_back(s);
    }
  }
}

}  // namespace radfarm::bench
