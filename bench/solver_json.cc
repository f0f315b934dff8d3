#include "bench/solver_json.h"

#include "bench/bench_json.h"
#include "bench/patch_error.h"

namespace radfarm::bench {
namespace {

using nlohmann::json;

json Point(const SweepPoint& p) {
  const SolverSettings& s = p.settings;
  return {{"sampler", std::string(SamplerName(s.sampler))},
          {"budget", p.budget},
          {"shot_rays", s.shot_rays},
          {"max_rays", s.max_rays},
          {"grid_step_degrees", s.grid_step_degrees},
          {"shooters_per_round", s.shooters_per_round},
          {"threads", s.threads},
          {"rays", p.rays},
          {"rounds", p.rounds},
          {"seconds", p.seconds},
          {"rays_per_second", p.rays_per_second},
          {"error", p.error},
          {"error_lit", p.error_lit},
          {"unshot_fraction", p.unshot_fraction},
          {"stop_reason", p.stop_reason}};
}

json Points(const std::vector<SweepPoint>& points) {
  json out = json::array();
  for (const SweepPoint& p : points) out.push_back(Point(p));
  return out;
}

json Sweep(const SceneSweep& s) {
  const Reference& r = s.reference;
  return {{"scene", s.scene},
          {"path", s.path},
          {"patches", s.patches},
          {"patch_size", s.patch_size},
          {"load_seconds", s.load_seconds},
          {"reference",
           {{"shot_rays", r.settings.shot_rays},
            {"rays", r.rays},
            {"rounds", r.rounds},
            {"seconds", r.seconds},
            {"patches_all", r.patches.all.size()},
            {"patches_lit", r.patches.lit.size()}}},
          {"points", Points(s.points)},
          {"grid_steps", Points(s.grid_steps)},
          {"grid_converged", Points(s.grid_converged)}};
}

json Raw(const RawThroughput& t) {
  return {{"scene", t.scene},
          {"patch_size", t.patch_size},
          {"patches", t.patches},
          {"rounds", t.rounds},
          {"rays", t.rays},
          {"batches", t.batches},
          {"planned_rays", t.planned_rays},
          {"planned_batches", t.planned_batches},
          {"threads", t.threads},
          {"repetitions", t.repetitions},
          {"raw_seconds", t.raw_seconds},
          {"packet_seconds", t.packet_seconds},
          {"runner_seconds", t.runner_seconds},
          {"pool_seconds", t.pool_seconds},
          {"sample_seconds", t.sample_seconds},
          {"raw_rays_per_second", t.raw_rays_per_second},
          {"packet_rays_per_second", t.packet_rays_per_second},
          {"runner_rays_per_second", t.runner_rays_per_second},
          {"pool_rays_per_second", t.pool_rays_per_second},
          {"sample_rays_per_second", t.sample_rays_per_second},
          {"packet_over_raw", t.packet_over_raw},
          {"runner_over_raw", t.runner_over_raw},
          {"pool_over_raw", t.pool_over_raw},
          {"same_hits", t.same_hits},
          {"escaped_rays", t.escaped_rays},
          {"back_rays", t.back_rays}};
}

json Seed(const SeedWorkload& s) {
  json tried = json::array();
  for (const EqualTimeCandidate& c : s.tried) {
    tried.push_back({{"point", Point(c.point)}, {"seed_seconds", c.seed_seconds}});
  }
  return {{"paper_seconds", kSeedPaperSeconds},
          {"seed", Point(s.seed)},
          {"one_thread_seconds", s.one_thread_seconds},
          {"repetitions", s.repetitions},
          {"match_repetitions", s.match_repetitions},
          {"patches", s.patches},
          {"tried", tried},
          {"seed_seconds_alongside", s.seed_seconds_alongside},
          {"at_floor", s.at_floor},
          {"equal_time", Point(s.equal_time.point)},
          {"error_ratio", s.error_ratio},
          {"error_ratio_lit", s.error_ratio_lit}};
}

}  // namespace

json RawBuildingsJson(const MachineInfo& machine, const std::vector<RawThroughput>& raw,
                      double total_seconds, const std::string& load_average_end) {
  json rows = json::array();
  for (const RawThroughput& t : raw) rows.push_back(Raw(t));
  return {{"program", "solver_bench --raw-buildings"},
          {"machine", MachineJson(machine)},
          {"load_average_end", load_average_end},
          {"total_seconds", total_seconds},
          {"raw", rows}};
}

json SolverBenchJson(const BenchReport& r) {
  const SweepConfig& c = r.sweep_config;
  json sweeps = json::array();
  for (const SceneSweep& s : r.sweeps) sweeps.push_back(Sweep(s));
  json raw = json::array();
  for (const RawThroughput& t : r.raw) raw.push_back(Raw(t));
  const SolverSettings defaults;
  return {{"program", "solver_bench"},
          {"quick", r.quick},
          {"machine", MachineJson(r.machine)},
          {"load_average_end", r.load_average_end},
          {"total_seconds", r.total_seconds},
          {"config",
           {{"repetitions", c.repetitions},
            {"tolerance", c.tolerance},
            {"seed", c.seed},
            {"reference_factor", c.reference_factor},
            {"reference_tolerance", c.reference_tolerance},
            {"reference_seed", c.reference_seed},
            {"grid_step_degrees", c.grid_step_degrees},
            {"grid_shooters_per_round", c.grid_shooters_per_round},
            {"dark_fraction", kDarkFraction},
            {"default_sampler", std::string(SamplerName(defaults.sampler))},
            {"default_tolerance", defaults.tolerance}}},
          {"sweeps", sweeps},
          {"raw", raw},
          {"seed", Seed(r.seed)}};
}

}  // namespace radfarm::bench
