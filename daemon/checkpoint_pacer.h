// CheckpointPacer: decides which rounds of a job write a checkpoint. A checkpoint is written
//   - at most every `min_seconds` (0: every round), the first `min_seconds` after the job's first
//     round (0: after its first round),
//   - never while the job's previous one is still being written (at 10^6 patches one is 50 MB and
//     may take longer than a round; a queue of them would only grow), and
//   - only once the job has run at least 1 / `time_share` times as long as the store thread
//     took to write its previous one since that one was queued, so writing checkpoints takes
//     at most about that share of the store thread's time and of the CPUs it shares with
//     the tracing (0: no such limit).
// A round without a checkpoint is still recorded, and its kept results let a restart replay it
// (daemon/result_journal.h), so skipping one costs a restart at most the rounds since the last.
// Pure bookkeeping: the loop thread calls it with the loop's clock.
#pragma once

#include <cstdint>
#include <map>

#include "store/job_store.h"

namespace radfarm::daemon {

class CheckpointPacer {
 public:
  CheckpointPacer(double min_seconds, double time_share)
      : min_seconds_(min_seconds), time_share_(time_share) {}

  // Whether job `id`'s round reduced at `now_ms` checkpoints; if so it counts as queued then.
  bool Due(store::JobId id, uint64_t now_ms);
  // The checkpoint Due allowed has been written, in `write_seconds` of the store thread's time
  // (or failed: pass 0).
  void Written(store::JobId id, double write_seconds);
  // The job's runner went (ended, paused, cancelled): its pace starts afresh; a checkpoint still
  // being written keeps the next one waiting.
  void Forget(store::JobId id);

 private:
  struct Job {
    bool any = false;        // a round has been reduced: the pace has started
    uint64_t queued_ms = 0;  // the last checkpoint queued, or the first round
    int in_flight = 0;
    double write_seconds = 0;  // the last written one's
  };
  double min_seconds_;
  double time_share_;
  std::map<store::JobId, Job> jobs_;
};

}  // namespace radfarm::daemon
