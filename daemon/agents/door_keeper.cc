#include "daemon/agents/door_keeper.h"

#include <algorithm>

namespace radfarm::daemon {

std::optional<uint64_t> DoorKeeper::Admit(uint64_t id) {
  ++counters_.accepted;
  waiting_.insert(id);
  std::optional<uint64_t> evict;
  if (waiting_.size() > max_) {
    evict = *waiting_.begin();
    waiting_.erase(waiting_.begin());
    ++counters_.evicted;
  }
  counters_.unauthenticated = waiting_.size();
  counters_.unauthenticated_peak =
      std::max(counters_.unauthenticated_peak, uint64_t(waiting_.size()));
  return evict;
}

void DoorKeeper::Authenticated(uint64_t id) {
  if (waiting_.erase(id) > 0) ++counters_.authenticated;
  counters_.unauthenticated = waiting_.size();
}

bool DoorKeeper::ClosedBeforeAuth(uint64_t id) {
  const bool counted = waiting_.erase(id) > 0;
  if (counted) ++counters_.closed_before_auth;
  counters_.unauthenticated = waiting_.size();
  return counted;
}

}  // namespace radfarm::daemon
