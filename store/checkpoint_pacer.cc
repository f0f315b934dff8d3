#include "store/checkpoint_pacer.h"

namespace radfarm::store {

bool CheckpointPacer::Due(JobId id, uint64_t now_ms) {
  Job& job = jobs_[id];
  if (job.in_flight > 0) return false;
  if (!job.any) {
    // The job's first round: the pace starts. With min_seconds the first checkpoint waits too.
    job.any = true;
    job.first_ms = job.queued_ms = now_ms;
    if (min_seconds_ > 0) return false;
  } else {
    const double since = double(now_ms - job.queued_ms) / 1000;
    if (min_seconds_ > 0 && since < min_seconds_) return false;
    const double running = double(now_ms - job.first_ms) / 1000;
    if (time_share_ > 0 && running * time_share_ < job.spent_seconds + job.write_seconds) {
      return false;
    }
  }
  job.queued_ms = now_ms;
  ++job.in_flight;
  return true;
}

void CheckpointPacer::Forget(JobId id) {
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return;
  if (it->second.in_flight > 0) {
    it->second = Job{.in_flight = it->second.in_flight};
  } else {
    jobs_.erase(it);
  }
}

void CheckpointPacer::Written(JobId id, double write_seconds) {
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) return;
  if (it->second.in_flight > 0) --it->second.in_flight;
  if (it->second.any) {
    it->second.write_seconds = write_seconds;
    it->second.spent_seconds += write_seconds;
  } else if (it->second.in_flight == 0) {
    jobs_.erase(it);  // forgotten while it was written
  }
}

}  // namespace radfarm::store
