#include "core/solve_stats.h"

namespace radfarm {

SolveStats StatsOf(const SolveTotals& totals, const EnergyAccount& energy) {
  SolveStats stats;
  stats.rays = totals.rays;
  stats.seconds = totals.seconds;
  stats.rays_per_second = totals.seconds > 0 ? double(totals.rays) / totals.seconds : 0;
  stats.escaped_rays = totals.escaped_rays;
  stats.backface_hits = totals.backface_hits;
  stats.emitted_power = energy.emitted;
  stats.absorbed_power = energy.absorbed;
  stats.escaped_power = energy.escaped;
  return stats;
}

}  // namespace radfarm
