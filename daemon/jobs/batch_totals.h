// BatchTotals: the batch counters of /metrics summed over jobs. A RoundScheduler counts from its
// job's start; JobRounds adds a runner's counts to its retired totals when the runner goes, so the
// totals (retired + running) only grow while the master runs, as Prometheus counters must.
#pragma once

#include <array>
#include <cstdint>

#include "daemon/scheduler/scheduler_counters.h"

namespace radfarm::daemon {

struct BatchTotals {
  uint64_t issued = 0;
  uint64_t speculative = 0;  // of issued: copies of an overdue lease
  uint64_t requeued = 0;
  uint64_t preempted = 0;  // live leases taken back for a higher-priority job
  uint64_t accepted = 0;
  std::array<uint64_t, scheduler::kDropReasonCount> dropped{};  // by scheduler::DropReason
  // Exact validation (JobRounds::verification, set by JobRounds::batch_totals, not by Add).
  uint64_t verified = 0;
  uint64_t verify_mismatches = 0;

  void Add(const scheduler::SchedulerCounters& counters);
  void Add(const BatchTotals& other);
};

}  // namespace radfarm::daemon
