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
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/result.h"
#include "cli/checkpoint_writer.h"
#include "codec/job_bundle.h"
#include "solve/solve_state.h"
#include "store/checkpoint_pacer.h"
#include "store/job_store.h"

namespace radfarm {

class RenderState {
 public:
  static Result<RenderState> Open(const std::string& db_path, const codec::JobBundle& bundle);

  // Where to start: the latest checkpoint (owned by this object), or null for a fresh job.
  const SolveState* resume() const { return resume_.get(); }
  store::JobId job_id() const { return job_; }

  // Records one round and its checkpoint (one transaction), keeping the last two checkpoints; a
  // refined mesh's scene is stored first (once per mesh). They are written on the writer's thread
  // (checkpoint_writer.h) while the next round runs; while a checkpoint is still being written, or
  // too soon after the last for its cost (store/checkpoint_pacer.h), the round is recorded
  // without one (a resume from the one before computes the same bits), and the
  // last round's state, if its checkpoint was left out, is written by Finish. Returns the error of
  // an earlier write. Do not move this object after the first call.
  Status SaveRound(const SolveState& state);
  // Writes what is left, then marks the job done.
  Status Finish();

  // A checkpoint written: its cost, and the time the render waited for it (the copy of the state).
  struct Report {
    uint32_t round = 0;
    store::CheckpointCost cost;
    double seconds = 0;  // on the writer's thread: the checkpoint and pruning
    double waited_seconds = 0;
  };
  // The checkpoints committed since the last call.
  std::vector<Report> TakeReports();

 private:
  struct Reports {
    std::mutex mu;
    std::vector<Report> done;
    std::vector<double> written_seconds;  // each checkpoint's, for the pacer
  };
  explicit RenderState(store::JobStore store)
      : store_(std::make_unique<store::JobStore>(std::move(store))),
        reports_(std::make_shared<Reports>()) {}
  Status QueueCheckpoint(const store::RoundRecord& round, store::Checkpoint checkpoint,
                         double waited_seconds);

  std::unique_ptr<store::JobStore> store_;  // on the heap: the writer keeps a reference
  store::JobId job_ = 0;
  // On the heap, so that resume_->refined_scene stays valid when the object moves.
  std::unique_ptr<SolveState> resume_;
  std::unique_ptr<PatchScene> resume_scene_;  // the refined mesh the checkpoint belongs to
  SolveTotals last_;                          // the totals at the previous round boundary
  // The refined scene stored last: its hash and the SolveState::refinements it was for.
  std::optional<std::string> scene_hash_;
  uint32_t scene_refinements_ = 0;
  // The last round recorded without its checkpoint, which Finish writes (its buffers reused).
  bool unsaved_ = false;
  SolveState unsaved_state_;
  store::RoundRecord unsaved_round_;
  std::optional<std::string> unsaved_scene_hash_;
  std::shared_ptr<Reports> reports_;
  // Which rounds write a checkpoint: one is written once the render has run 20 times as long as
  // the last took to write (the writer shares the CPUs with the render).
  store::CheckpointPacer pacer_{0, store::kDefaultCheckpointTimeShare};
  std::unique_ptr<CheckpointWriter> writer_;  // after store_: it goes first
};

}  // namespace radfarm
