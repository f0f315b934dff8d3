#include "daemon/console/farm_metrics.h"

#include <string>

#include "store/job_state.h"

namespace radfarm::daemon {
namespace {

// "not the holder" -> "not_the_holder": label values stay one word.
std::string Label(std::string_view name) {
  std::string label(name);
  for (char& c : label) c = c == ' ' ? '_' : c;
  return label;
}

bool IsRejection(scheduler::DropReason r) {
  using R = scheduler::DropReason;
  return r == R::kWrongBatch || r == R::kNotHolder || r == R::kBlocklisted || r == R::kInvalid;
}

}  // namespace

web::FarmMetrics FarmMetricsOf(const nlohmann::json& jobs, const nlohmann::json& agents,
                               const BatchTotals& batches,
                               const LatencyHistogram& checkpoint_latency,
                               size_t store_queue_depth) {
  web::FarmMetrics m;
  using store::JobState;
  for (JobState s : {JobState::kQueued, JobState::kRunning, JobState::kPaused, JobState::kHeld,
                     JobState::kDone, JobState::kFailed, JobState::kCancelled}) {
    m.jobs_by_state[std::string(store::JobStateName(s))] = 0;
  }
  for (const auto& job : jobs) {
    ++m.jobs_by_state[job.value("state", std::string("unknown"))];
    m.rays_total += job.value("rays", uint64_t{0});
    if (job.value("state", std::string()) == "running") {
      m.rays_per_second += job.value("rays_per_second", 0.0);
    }
  }
  m.agents_by_state = {{"busy", 0}, {"idle", 0}, {"stale", 0}};
  for (const auto& agent : agents) {
    const char* state = agent.value("stale", false)              ? "stale"
                        : agent.value("leases", uint64_t{0}) > 0 ? "busy"
                                                                 : "idle";
    ++m.agents_by_state[state];
  }
  m.batches_issued = batches.issued;
  m.batches_reissued_overdue = batches.speculative;
  m.batches_reissued_requeued = batches.requeued;
  m.leases_preempted = batches.preempted;
  m.results_accepted = batches.accepted;
  m.batches_verified = batches.verified;
  m.verify_mismatches = batches.verify_mismatches;
  for (size_t i = 1; i < batches.dropped.size(); ++i) {
    const auto reason = static_cast<scheduler::DropReason>(i);
    auto& into = IsRejection(reason) ? m.results_rejected : m.results_dropped;
    into[Label(scheduler::DropReasonName(reason))] = batches.dropped[i];
  }
  m.checkpoint_seconds = checkpoint_latency;
  m.store_queue_depth = store_queue_depth;
  return m;
}

}  // namespace radfarm::daemon
