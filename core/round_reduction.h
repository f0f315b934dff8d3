// RoundReduction: folds a round's batch results into the solver as they arrive, in any order,
// with ProgressiveSolver::ApplyRound's arithmetic in ApplyRound's order, so the same bits. A shot
// is applied as soon as its batches and those of every earlier shot are in; its results are then
// freed. What is held is the results that arrived ahead of the first incomplete shot, not the
// whole round's: a final gather's results are about 16 bytes per patch hit per batch, some 20 KB
// per patch at 2048 gather rays, where the solver's own state is under 100 bytes per patch.
//
// Not thread-safe: one caller at a time. The solver must not be used otherwise until Finish.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/batch.h"
#include "core/progressive_solver.h"

namespace radfarm {

class RoundReduction {
 public:
  // Starts folding `plan` (ProgressiveSolver::BeginRound). `plan` and `solver` must outlive this.
  RoundReduction(ProgressiveSolver& solver, const RoundPlan& plan);

  // The result of plan.batches[batch]. False, and nothing changes, for a batch out of range or
  // one already added.
  bool Add(size_t batch, BatchResult result);

  // Every batch is in (and so every shot applied).
  bool complete() const { return next_shot_ == shot_first_batch_.size() - 1; }
  // Ends the round (ProgressiveSolver::EndRound). Requires complete().
  void Finish();

  uint64_t escaped_rays() const { return escaped_rays_; }
  uint64_t back_rays() const { return back_rays_; }
  // Results held now, waiting for an earlier shot; and the most held at once so far.
  size_t held() const { return held_; }
  size_t peak_held() const { return peak_held_; }

 private:
  // Applies every shot whose batches are all in, in shot order, from next_shot_ on.
  void ApplyReadyShots();

  ProgressiveSolver& solver_;
  const RoundPlan& plan_;
  std::vector<size_t> shot_first_batch_;  // shot s's batches: [first[s], first[s + 1])
  // A bit a batch for the batches in (a round at 10^6 patches has about a million), and the
  // results held, by batch.
  std::vector<bool> in_;
  std::unordered_map<size_t, BatchResult> held_results_;
  std::vector<uint32_t> missing_;  // per shot: batches not yet in
  size_t next_shot_ = 0;
  size_t held_ = 0;
  size_t peak_held_ = 0;
  uint64_t escaped_rays_ = 0;
  uint64_t back_rays_ = 0;
  bool finished_ = false;
};

}  // namespace radfarm
