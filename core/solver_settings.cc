#include "core/solver_settings.h"

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

}  // namespace radfarm
