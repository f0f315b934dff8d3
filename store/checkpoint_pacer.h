// CheckpointPacer: decides which rounds of a job write a checkpoint. A checkpoint is written
//   - at most every `min_seconds` (0: every round), the first `min_seconds` after the job's first
//     round (0: after its first round),
//   - never while the job's previous one is still being written (a big scene's is large and may
//     take longer than a round; a queue of them would only grow), and
//   - only while the job's checkpoints, this one included (priced as the last), have taken at
//     most `time_share` of the time since its first round (0: no such limit). A checkpoint's
//     time is from its queueing to its commit, as Written is told. The first round's is always
//     written; after it, a job whose checkpoints take 2 s writes one every 40 s at 5 %.
// A round without a checkpoint is still recorded, and its kept results let a restart replay it
// (daemon/jobs/result_journal.h), so skipping one costs a restart at most the rounds since the
// last. radfarmd paces each job's checkpoints so, and `radfarm render --db` its one job's. Pure
// bookkeeping: one thread calls it (radfarmd's loop thread, the render's), with its clock.
#pragma once

#include <cstdint>
#include <map>

#include "store/job_store.h"

namespace radfarm::store {

// At most this share of a job's time goes to writing checkpoints, by default.
inline constexpr double kDefaultCheckpointTimeShare = 0.05;

class CheckpointPacer {
 public:
  CheckpointPacer(double min_seconds, double time_share)
      : min_seconds_(min_seconds), time_share_(time_share) {}

  // Whether job `id`'s round reduced at `now_ms` checkpoints; if so it counts as queued then.
  bool Due(JobId id, uint64_t now_ms);
  // The checkpoint Due allowed has been written, in `write_seconds` of the store thread's time
  // (or failed: pass 0).
  void Written(JobId id, double write_seconds);
  // The job's runner went (ended, paused, cancelled): its pace starts afresh; a checkpoint still
  // being written keeps the next one waiting.
  void Forget(JobId id);

 private:
  struct Job {
    bool any = false;          // a round has been reduced: the pace has started
    uint64_t first_ms = 0;     // the first round
    uint64_t queued_ms = 0;    // the last checkpoint queued, or the first round
    double spent_seconds = 0;  // the checkpoints written
    int in_flight = 0;
    double write_seconds = 0;  // the last written one's
  };
  double min_seconds_;
  double time_share_;
  std::map<JobId, Job> jobs_;
};

}  // namespace radfarm::store
