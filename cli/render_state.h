// RenderState: `radfarm render --db FILE`, an embedded render that keeps its rounds in a job store
// (the master's SQLite format, daemon/store/) so that a render killed midway continues where it
// stopped when the same command runs again, and ends with the same bits as an uninterrupted one.
//
// The job is recognised by the SHA-256 of its bundle (scene and settings, with the thread count
// left out: it never changes the result). A job that is found resumes from its latest checkpoint;
// one that already finished resumes from its last one, so its outputs are written again at no cost.
#pragma once

#include <optional>
#include <string>

#include "codec/job_bundle.h"
#include "core/result.h"
#include "core/solve.h"
#include "daemon/store/job_store.h"

namespace radfarm {

class RenderState {
 public:
  static Result<RenderState> Open(const std::string& db_path, const codec::JobBundle& bundle);

  // Where to start: the latest checkpoint, or nullptr for a fresh job.
  const SolveCheckpoint* resume() const { return resume_ ? &*resume_ : nullptr; }
  store::JobId job_id() const { return job_; }

  // Commits one round and its checkpoint (one transaction), keeping the last two checkpoints.
  Status SaveRound(const SolveCheckpoint& state);
  Status Finish();

 private:
  RenderState(store::JobStore store) : store_(std::move(store)) {}

  store::JobStore store_;
  store::JobId job_ = 0;
  std::optional<SolveCheckpoint> resume_;
  SolveCheckpoint last_;  // the totals at the previous round boundary
};

}  // namespace radfarm
