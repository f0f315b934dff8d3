#include "daemon/agents/job_blocklist.h"

#include <algorithm>

namespace radfarm::daemon {

std::optional<scheduler::TimePoint> JobBlocklist::Strike(int64_t job, const std::string& agent,
                                                         scheduler::TimePoint now) {
  Prune(now);
  Entry& entry = entries_[{job, agent}];
  while (!entry.strikes.empty() && entry.strikes.front() + duration_ <= now) {
    entry.strikes.pop_front();
  }
  entry.strikes.push_back(now);
  if (entry.strikes.size() < kStrikes) return std::nullopt;
  entry.strikes.clear();  // a new blocklisting starts counting afresh when it ends
  entry.until = now + duration_;
  return entry.until;
}

scheduler::TimePoint JobBlocklist::Block(int64_t job, const std::string& agent,
                                         scheduler::TimePoint now) {
  Prune(now);
  Entry& entry = entries_[{job, agent}];
  entry.strikes.clear();
  entry.until = now + duration_;
  return *entry.until;
}

std::optional<scheduler::TimePoint> JobBlocklist::BlockedUntil(int64_t job,
                                                               const std::string& agent,
                                                               scheduler::TimePoint now) const {
  const auto it = entries_.find({job, agent});
  if (it == entries_.end() || !it->second.until || *it->second.until <= now) return std::nullopt;
  return it->second.until;
}

uint32_t JobBlocklist::Strikes(int64_t job, const std::string& agent,
                               scheduler::TimePoint now) const {
  const auto it = entries_.find({job, agent});
  if (it == entries_.end()) return 0;
  return static_cast<uint32_t>(
      std::count_if(it->second.strikes.begin(), it->second.strikes.end(),
                    [&](scheduler::TimePoint t) { return now < t + duration_; }));
}

void JobBlocklist::Prune(scheduler::TimePoint now) {
  std::erase_if(entries_, [&](const auto& item) {
    const Entry& e = item.second;
    const bool strikes_gone = e.strikes.empty() || e.strikes.back() + duration_ <= now;
    return strikes_gone && (!e.until || *e.until <= now);
  });
}

}  // namespace radfarm::daemon
