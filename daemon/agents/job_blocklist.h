// JobBlocklist: which agents may not work for which job, by identity. An agent whose results
// authenticate (so the wire is not to blame) but fail CheckBatchOutcome earns a strike for that
// job; kStrikes strikes within `duration` blocklist it for that job until `duration` after the
// last. Strikes and blocklistings expire; other jobs are not affected.
//
// The identity is the agent's authenticated name (its Hello, proven by the handshake), never its
// host or address: a healthy agent on the same machine keeps working, and per-agent credentials
// will make the name a per-agent key's.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::daemon {

class JobBlocklist {
 public:
  static constexpr uint32_t kStrikes = 3;  // as Flamenco's task failures per worker

  explicit JobBlocklist(scheduler::Duration duration) : duration_(duration) {}

  // Records one invalid result of `agent` for `job`. Returns when the blocklisting ends if this
  // strike blocklists the agent, else nullopt.
  std::optional<scheduler::TimePoint> Strike(int64_t job, const std::string& agent,
                                             scheduler::TimePoint now);
  // Blocklists `agent` for `job` at once, without strikes: one of its results failed exact
  // validation (daemon/jobs/batch_verifier.h), which no wire fault can cause. Returns until when.
  scheduler::TimePoint Block(int64_t job, const std::string& agent, scheduler::TimePoint now);
  // Until when `agent` is blocklisted for `job`; nullopt if it is not (or no longer).
  std::optional<scheduler::TimePoint> BlockedUntil(int64_t job, const std::string& agent,
                                                   scheduler::TimePoint now) const;
  // Strikes of `agent` for `job` still counting at `now`.
  uint32_t Strikes(int64_t job, const std::string& agent, scheduler::TimePoint now) const;
  // (job, agent) pairs remembered: strikes or a blocklisting not yet expired, at the last Strike.
  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::deque<scheduler::TimePoint> strikes;  // oldest first
    std::optional<scheduler::TimePoint> until;
  };
  using Key = std::pair<int64_t, std::string>;

  // Forgets entries with nothing left in force (strikes are rare: a scan is cheap).
  void Prune(scheduler::TimePoint now);

  scheduler::Duration duration_;
  std::map<Key, Entry> entries_;
};

}  // namespace radfarm::daemon
