#include "core/round_reduction.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace radfarm {

RoundReduction::RoundReduction(ProgressiveSolver& solver, const RoundPlan& plan)
    : solver_(solver), plan_(plan), in_(plan.batches.size(), false) {
  // plan.batches holds every shot's batches in shot order (ProgressiveSolver::PlanRound).
  shot_first_batch_.reserve(plan.shots.size() + 1);
  missing_.reserve(plan.shots.size());
  size_t b = 0;
  for (const Shot& shot : plan.shots) {
    shot_first_batch_.push_back(b);
    while (b < plan.batches.size() && plan.batches[b].shooter == shot.shooter) ++b;
    missing_.push_back(static_cast<uint32_t>(b - shot_first_batch_.back()));
  }
  shot_first_batch_.push_back(b);
  solver_.BeginRound(plan);
  ApplyReadyShots();  // shots without batches
}

bool RoundReduction::Add(size_t batch, BatchResult result) {
  if (batch >= in_.size() || in_[batch]) return false;
  in_[batch] = true;
  const size_t shot = static_cast<size_t>(std::upper_bound(shot_first_batch_.begin(),
                                                           shot_first_batch_.end(), batch) -
                                          shot_first_batch_.begin()) -
                      1;
  escaped_rays_ += result.escaped_rays;
  back_rays_ += result.back_rays;
  held_results_.emplace(batch, std::move(result));
  --missing_[shot];
  peak_held_ = std::max(peak_held_, ++held_);
  ApplyReadyShots();
  return true;
}

void RoundReduction::ApplyReadyShots() {
  std::vector<BatchResult> shot_results;
  while (next_shot_ < missing_.size() && missing_[next_shot_] == 0) {
    const size_t first = shot_first_batch_[next_shot_];
    const size_t last = shot_first_batch_[next_shot_ + 1];
    shot_results.clear();
    for (size_t b = first; b < last; ++b) {
      shot_results.push_back(std::move(held_results_.extract(b).mapped()));
    }
    // Applied: the results go; in_ keeps them marked against a repeat.
    solver_.ApplyShot(plan_, next_shot_, shot_results);
    held_ -= last - first;
    ++next_shot_;
  }
}

void RoundReduction::Finish() {
  if (!complete() || finished_) throw std::logic_error("RoundReduction::Finish before all batches");
  solver_.EndRound(plan_);
  finished_ = true;
}

}  // namespace radfarm
