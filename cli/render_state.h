// RenderState: `radfarm render --db FILE`, an embedded render that keeps its rounds in a job store
// (the master's SQLite format, store/) so that a render killed midway continues where it
// stopped when the same command runs again, and ends with the same bits as an uninterrupted one.
//
// The job is recognised by the SHA-256 of its bundle (scene and settings, with the thread count
// left out: it never changes the result). A job that is found resumes from its latest checkpoint;
// one that already finished resumes from its last one, so its outputs are written again at no cost.
// With adaptive refinement a checkpoint also names the refined mesh (its scene blob, stored by
// hash as the master stores it) and the refinement points passed (solve/solve_state.h).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "base/result.h"
#include "codec/job_bundle.h"
#include "solve/solve_state.h"
#include "store/job_store.h"

namespace radfarm {

class RenderState {
 public:
  static Result<RenderState> Open(const std::string& db_path, const codec::JobBundle& bundle);

  // Where to start: the latest checkpoint (owned by this object), or null for a fresh job.
  const SolveState* resume() const { return resume_.get(); }
  store::JobId job_id() const { return job_; }

  // Commits one round and its checkpoint (one transaction), keeping the last two checkpoints; a
  // refined mesh's scene is stored first (once per mesh).
  Status SaveRound(const SolveState& state);
  Status Finish();

 private:
  RenderState(store::JobStore store) : store_(std::move(store)) {}

  store::JobStore store_;
  store::JobId job_ = 0;
  // On the heap, so that resume_->refined_scene stays valid when the object moves.
  std::unique_ptr<SolveState> resume_;
  std::unique_ptr<PatchScene> resume_scene_;  // the refined mesh the checkpoint belongs to
  SolveTotals last_;                          // the totals at the previous round boundary
  // The refined scene stored last: its hash and the SolveState::refinements it was for.
  std::optional<std::string> scene_hash_;
  uint32_t scene_refinements_ = 0;
};

}  // namespace radfarm
