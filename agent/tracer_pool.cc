#include "agent/tracer_pool.h"

#include <chrono>

namespace radfarm::agent {

BatchOutcome TracerPool::Run(const std::shared_ptr<const PreparedScene>& scene,
                             const std::shared_ptr<const RaySampler>& sampler, const Batch& batch) {
  std::unique_ptr<Slot> slot = Borrow(scene.get(), sampler.get());
  if (slot->scene != scene || slot->sampler != sampler) {
    slot->runner.reset();  // bound to the old pair: unbind before letting it go
    slot->scene = scene;
    slot->sampler = sampler;
    slot->runner.emplace(scene->scene, *scene->caster, *sampler);
  }
  const auto start = std::chrono::steady_clock::now();
  BatchOutcome outcome;
  outcome.result = slot->runner->Run(batch);
  outcome.compute_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  GiveBack(std::move(slot));
  return outcome;
}

std::unique_ptr<TracerPool::Slot> TracerPool::Borrow(const PreparedScene* scene,
                                                     const RaySampler* sampler) {
  std::lock_guard lock(mutex_);
  if (free_.empty()) return std::make_unique<Slot>();
  size_t pick = free_.size() - 1;
  for (size_t i = 0; i < free_.size(); ++i) {
    if (free_[i]->scene.get() == scene && free_[i]->sampler.get() == sampler) pick = i;
  }
  std::unique_ptr<Slot> slot = std::move(free_[pick]);
  free_.erase(free_.begin() + static_cast<ptrdiff_t>(pick));
  return slot;
}

void TracerPool::GiveBack(std::unique_ptr<Slot> slot) {
  std::lock_guard lock(mutex_);
  free_.push_back(std::move(slot));
}

}  // namespace radfarm::agent
