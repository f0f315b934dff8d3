// The farm's figures for Prometheus (GET /metrics) and their text exposition format (version
// 0.0.4: "# HELP", "# TYPE", then one "name{label="value"} number" line per series). The metric
// names and what they count are listed in docs/OPERATIONS.md, "Metrics".
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "base/latency_histogram.h"

namespace radfarm::web {

struct FarmMetrics {
  std::map<std::string, uint64_t> jobs_by_state;    // every job state, 0 included
  std::map<std::string, uint64_t> agents_by_state;  // busy, idle, stale
  double rays_per_second = 0;                       // summed over the running jobs
  uint64_t rays_total = 0;                          // rays of every job so far
  // Batches, since the master started (the running jobs' schedulers plus the finished ones').
  uint64_t batches_issued = 0;             // attempts handed to agents
  uint64_t batches_reissued_overdue = 0;   // copies of an overdue lease
  uint64_t batches_reissued_requeued = 0;  // put back after a loss or a return
  uint64_t leases_preempted = 0;           // taken back for a higher-priority job
  uint64_t results_accepted = 0;           // the first valid result of a batch
  uint64_t batches_verified = 0;           // computed again by the master and compared bit for bit
  uint64_t verify_mismatches = 0;  // of those: the agent's bits differed (it was blocklisted)
  std::map<std::string, uint64_t> results_rejected;  // by reason: the agent is at fault
  std::map<std::string, uint64_t> results_dropped;   // by reason: too late or repeated
  LatencyHistogram checkpoint_seconds;               // queued on the store -> committed
  uint64_t store_queue_depth = 0;                    // store operations waiting to run
  // Accepted results kept in the store for a restart (daemon/jobs/result_journal.h), the writes
  // that kept them, and batches a restart found there and did not lease again.
  uint64_t round_results_kept = 0;
  uint64_t round_result_writes = 0;
  uint64_t batches_restored = 0;
  // Final-gather batches computed ahead of their round and accepted there
  // (daemon/jobs/gather_ahead.h).
  uint64_t gather_ahead_batches = 0;
};

// The exposition text; series in a fixed order, labels sorted, numbers in their shortest exact
// form ("1e+06" style never: counts are integers, rates have up to 17 significant digits).
std::string FormatMetrics(const FarmMetrics& metrics);

}  // namespace radfarm::web
