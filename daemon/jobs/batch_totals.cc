#include "daemon/jobs/batch_totals.h"

namespace radfarm::daemon {

void BatchTotals::Add(const scheduler::SchedulerCounters& c) {
  issued += c.attempts_issued;
  speculative += c.speculative_attempts;
  requeued += c.leases_requeued;
  preempted += c.leases_preempted;
  accepted += c.results_accepted;
  for (size_t i = 0; i < dropped.size(); ++i) dropped[i] += c.results_dropped[i];
}

void BatchTotals::Add(const BatchTotals& o) {
  issued += o.issued;
  speculative += o.speculative;
  requeued += o.requeued;
  preempted += o.preempted;
  accepted += o.accepted;
  for (size_t i = 0; i < dropped.size(); ++i) dropped[i] += o.dropped[i];
}

}  // namespace radfarm::daemon
