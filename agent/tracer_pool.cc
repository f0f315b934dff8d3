#include "agent/tracer_pool.h"

#include <chrono>

namespace radfarm::agent {
namespace {

ResultTamper tamper_for_testing = nullptr;  // set before any worker thread starts

}  // namespace

void SetResultTamperForTesting(ResultTamper tamper) { tamper_for_testing = tamper; }

BatchOutcome TracerPool::Run(const std::shared_ptr<const PreparedScene>& scene,
                             const std::shared_ptr<const RaySampler>& sampler, const Batch& batch) {
  return std::move(RunAll(scene, sampler, {batch}).front());
}

std::vector<BatchOutcome> TracerPool::RunAll(const std::shared_ptr<const PreparedScene>& scene,
                                             const std::shared_ptr<const RaySampler>& sampler,
                                             const std::vector<Batch>& batches) {
  std::unique_ptr<Slot> slot = Borrow(scene, sampler);
  std::vector<BatchOutcome> outcomes;
  outcomes.reserve(batches.size());
  auto start = std::chrono::steady_clock::now();
  for (const Batch& batch : batches) {
    BatchOutcome outcome;
    outcome.result = slot->runner->Run(batch);
    if (tamper_for_testing != nullptr) tamper_for_testing(batch, outcome.result);
    const auto end = std::chrono::steady_clock::now();
    outcome.compute_seconds = std::chrono::duration<double>(end - start).count();
    start = end;
    outcomes.push_back(std::move(outcome));
  }
  GiveBack(std::move(slot));
  return outcomes;
}

std::unique_ptr<TracerPool::Slot> TracerPool::Borrow(
    const std::shared_ptr<const PreparedScene>& scene,
    const std::shared_ptr<const RaySampler>& sampler) {
  std::unique_ptr<Slot> slot;
  {
    std::lock_guard lock(mutex_);
    if (free_.empty()) {
      slot = std::make_unique<Slot>();
    } else {
      size_t pick = free_.size() - 1;
      for (size_t i = 0; i < free_.size(); ++i) {
        if (free_[i]->scene == scene && free_[i]->sampler == sampler) pick = i;
      }
      slot = std::move(free_[pick]);
      free_.erase(free_.begin() + static_cast<ptrdiff_t>(pick));
    }
  }
  if (slot->scene != scene || slot->sampler != sampler) {
    slot->runner.reset();  // bound to the old pair: unbind before letting it go
    slot->scene = scene;
    slot->sampler = sampler;
    slot->runner.emplace(scene->shapes, *scene->caster, *sampler);
  }
  return slot;
}

void TracerPool::GiveBack(std::unique_ptr<Slot> slot) {
  std::lock_guard lock(mutex_);
  free_.push_back(std::move(slot));
}

}  // namespace radfarm::agent
