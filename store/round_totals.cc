#include "store/round_totals.h"

namespace radfarm::store {

RoundTotals TotalsUpToRound(std::span<const RoundRecord> rounds, uint32_t round) {
  RoundTotals totals;
  for (const RoundRecord& r : rounds) {
    if (r.round > round) break;
    ++totals.rounds;
    totals.rays += r.rays;
    totals.escaped_rays += r.escaped_rays;
    totals.back_rays += r.back_rays;
    totals.seconds += r.duration_seconds;
    totals.unshot_fraction = r.unshot_fraction;
  }
  return totals;
}

}  // namespace radfarm::store
