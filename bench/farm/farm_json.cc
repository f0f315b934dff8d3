#include "bench/farm/farm_json.h"

#include "bench/bench_json.h"
#include "bench/farm/scaling_suite.h"

namespace radfarm::bench {
namespace {

using nlohmann::json;

json Setup(const RealComputeSetup& s) {
  return {{"name", s.name},
          {"detail", s.detail},
          {"rays", s.rays},
          {"rounds", s.rounds},
          {"rays_per_second", s.rays_per_second},
          {"solve_seconds", s.solve_seconds},
          {"wall_seconds", s.wall_seconds},
          {"cpu_seconds", s.cpu_seconds},
          {"agents_cpu_seconds", s.agents_cpu_seconds},
          {"patches_identical", s.patches_identical}};
}

json Sample(const ScalingSample& s) {
  return {{"job_rays", s.job_rays},
          {"rounds", s.rounds},
          {"batches", s.batches},
          {"computed_rays", s.computed_rays},
          {"wall_seconds", s.wall_seconds},
          {"bytes_sent", s.bytes_sent},
          {"bytes_received", s.bytes_received},
          {"scene_bytes", s.scene_bytes},
          {"utilisation_mean", s.utilisation_mean},
          {"utilisation_min", s.utilisation_min},
          {"efficiency", s.efficiency},
          {"master_cpu_seconds", s.master_cpu_seconds},
          {"master_connect_cpu_seconds", s.master_connect_cpu_seconds},
          {"master_loop_cpu_seconds", s.master_loop_cpu_seconds},
          {"master_loop_connect_cpu_seconds", s.master_loop_connect_cpu_seconds},
          {"frames", s.frames},
          {"swarm_cpu_seconds", s.swarm_cpu_seconds},
          {"mean_lateness", s.mean_lateness},
          {"max_lateness", s.max_lateness},
          {"connect_seconds", s.connect_seconds},
          {"idle_between_rounds", s.idle.between_rounds},
          {"idle_within_rounds", s.idle.within_rounds},
          {"idle_round_starts", s.idle.round_starts},
          {"idle_round_tails", s.idle.round_tails},
          {"agent_errors", s.agent_errors},
          {"first_error", s.first_error}};
}

json Case(const ScalingRow& row) {
  const ScalingCase& c = row.config;
  json samples = json::array();
  for (const ScalingSample& s : row.samples) samples.push_back(Sample(s));
  return {{"group", row.group},
          {"agents", c.agents},
          {"rays_per_second", c.rays_per_second},
          {"latency_ms", c.latency_ms},
          {"shot_rays", c.shot_rays},
          {"rounds", c.rounds},
          {"master_flags", c.master_flags},
          {"samples", samples}};
}

}  // namespace

json FarmBenchJson(const FarmBenchReport& r) {
  json out = {{"program", "farm_bench"},
              {"quick", r.quick},
              {"machine", MachineJson(r.machine)},
              {"load_average_end", r.load_average_end},
              {"total_seconds", r.total_seconds},
              {"radfarmd", r.radfarmd},
              {"open_file_limit", r.open_file_limit},
              {"real", nullptr},
              {"simulated", nullptr}};
  if (r.has_real) {
    json setups = json::array();
    for (const RealComputeSetup& s : r.real.setups) setups.push_back(Setup(s));
    out["real"] = {{"job", r.real.job}, {"setups", setups}};
  }
  if (!r.scaling.empty()) {
    json cases = json::array();
    for (const ScalingRow& row : r.scaling) cases.push_back(Case(row));
    out["simulated"] = {{"repetitions", r.repetitions},
                        {"round_seconds", r.round_seconds},
                        {"office_rays_per_second", kOfficeRaysPerSecond},
                        {"cases", cases}};
  }
  return out;
}

}  // namespace radfarm::bench
