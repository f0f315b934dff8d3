// What the scheduler reports for status pages and logs (RoundScheduler::counters()).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::scheduler {

struct AgentCounters {
  AgentId agent = 0;
  uint32_t leases_held = 0;     // live attempts it holds
  uint32_t lease_capacity = 0;  // how many it may hold now
  double rays_per_second = 0;   // smoothed; 0 until its first result
  bool blocklisted = false;
  uint64_t results_accepted = 0;
};

struct SchedulerCounters {
  // The current round (all zero between rounds).
  bool round_active = false;
  uint32_t round = 0;
  uint64_t batches = 0;
  uint64_t batches_queued = 0;  // waiting for an agent (fresh or handed back)
  uint64_t batches_leased = 0;  // at least one live attempt, no result yet
  uint64_t batches_done = 0;
  // Since the scheduler was made.
  uint64_t attempts_issued = 0;
  uint64_t speculative_attempts = 0;  // of attempts_issued: copies of an overdue or end-game lease
  uint64_t takeovers = 0;             // of attempts_issued: leases taken over from a busy agent
  uint64_t leases_requeued = 0;       // batches put back after a loss, return or revocation
  uint64_t leases_preempted = 0;      // live leases taken back for a higher-priority job
  uint64_t results_accepted = 0;
  std::array<uint64_t, kDropReasonCount> results_dropped{};  // by DropReason; [kNone] unused
  std::vector<AgentCounters> agents;                         // increasing agent id

  uint64_t dropped(DropReason reason) const { return results_dropped[size_t(reason)]; }
};

}  // namespace radfarm::scheduler
