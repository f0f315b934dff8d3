#include "core/round_reduction.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace radfarm {

RoundReduction::RoundReduction(ProgressiveSolver& solver, const RoundPlan& plan)
    : solver_(solver), plan_(plan), results_(plan.batches.size()) {
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
  if (batch >= results_.size() || results_[batch].has_value()) return false;
  const size_t shot = static_cast<size_t>(std::upper_bound(shot_first_batch_.begin(),
                                                           shot_first_batch_.end(), batch) -
                                          shot_first_batch_.begin()) -
                      1;
  escaped_rays_ += result.escaped_rays;
  back_rays_ += result.back_rays;
  results_[batch] = std::move(result);
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
    for (size_t b = first; b < last; ++b) shot_results.push_back(std::move(*results_[b]));
    solver_.ApplyShot(plan_, next_shot_, shot_results);
    // Applied: the results go, the slots stay marked as in (an empty result) against a repeat.
    for (size_t b = first; b < last; ++b) results_[b].emplace();
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
