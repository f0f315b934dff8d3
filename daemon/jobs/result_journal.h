// ResultJournal: writes the accepted batch results of each job's running round to the store
// (JobStore::SaveRoundResults), so a restarted master leases again only the batches it had not
// received (store/README.md: round_results).
//
// Group commit: each job has at most one write queued on the store thread. Results accepted while
// it runs wait on the loop thread and go together in the next write, so a farm that answers
// faster than the store commits gets bigger transactions, not a longer store queue, and one that
// answers slowly gets each result written at once. The loop thread never waits on the store.
//
// A write that fails loses nothing but the shortcut: the results are in the fold already, and a
// restart computes them again. It is logged (once per job until a write succeeds again).
//
// Threads: loop thread only; the writes run on the store thread.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "daemon/jobs/store_thread.h"
#include "store/job_store.h"

namespace radfarm::daemon {

struct JournalCounters {
  uint64_t results_written = 0;    // committed
  uint64_t writes = 0;             // transactions committed
  uint64_t results_failed = 0;     // in writes that failed
  uint64_t results_discarded = 0;  // waiting when their job went
};

class ResultJournal {
 public:
  explicit ResultJournal(StoreThread& store) : store_(store) {}
  ResultJournal(const ResultJournal&) = delete;
  ResultJournal& operator=(const ResultJournal&) = delete;

  // Queues `results` of job `job` for the store. Those of a round written after its checkpoint
  // (they waited while it was queued) are deleted by the next checkpoint and never read: a
  // restart reads only rounds after its checkpoint.
  void Add(store::JobId job, std::vector<store::StoredBatchResult> results);
  // The job left (finished, failed, cancelled, paused): what waits is not written, so nothing is
  // written after a job's last checkpoint.
  void Forget(store::JobId job);
  const JournalCounters& counters() const { return counters_; }

 private:
  struct JobQueue {
    std::vector<store::StoredBatchResult> waiting;
    bool writing = false;
    bool failing = false;  // the last write failed (logged once)
  };
  void Write(store::JobId job);

  StoreThread& store_;
  std::map<store::JobId, JobQueue> jobs_;
  JournalCounters counters_;
};

}  // namespace radfarm::daemon
