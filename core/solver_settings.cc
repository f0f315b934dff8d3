#include "core/solver_settings.h"

#include <algorithm>

namespace radfarm {

std::string_view SamplerName(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::kGrid:
      return "grid";
    case SamplerKind::kRandom:
      return "random";
    case SamplerKind::kSobol:
      return "sobol";
  }
  return "unknown";
}

bool ParseSamplerName(std::string_view name, SamplerKind* kind) {
  for (SamplerKind k : {SamplerKind::kGrid, SamplerKind::kRandom, SamplerKind::kSobol}) {
    if (SamplerName(k) == name) {
      *kind = k;
      return true;
    }
  }
  return false;
}

uint64_t BudgetShare(const SolverSettings& settings, uint64_t share, double rays_per_second) {
  uint64_t allowance = 0;
  if (settings.max_rays > 0) allowance = std::max<uint64_t>(1, settings.max_rays / share);
  if (settings.max_seconds > 0) {
    const double rays = settings.max_seconds * rays_per_second / double(share);
    const uint64_t by_time = static_cast<uint64_t>(std::clamp(rays, 1.0, 1e18));
    allowance = allowance > 0 ? std::min(allowance, by_time) : by_time;
  }
  return allowance;
}

}  // namespace radfarm
