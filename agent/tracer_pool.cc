#include "agent/tracer_pool.h"

#include <chrono>
#include <span>

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
  std::vector<BatchOutcome> outcomes(batches.size());
  std::vector<BatchResult> results;
  auto start = std::chrono::steady_clock::now();
  // A group of short batches is traced together (BatchTracer::RunMany) and timed as one; each
  // of its batches is given the group's time in proportion to its rays.
  for (size_t begin = 0; begin < batches.size();) {
    const size_t end = BatchTracer::GroupEnd(batches, begin);
    results.resize(end - begin);
    slot->runner->RunMany(std::span(batches).subspan(begin, end - begin), results.data());
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    uint64_t rays = 0;
    for (size_t k = begin; k < end; ++k) rays += batches[k].ray_count;
    for (size_t k = begin; k < end; ++k) {
      BatchOutcome& outcome = outcomes[k];
      outcome.result = std::move(results[k - begin]);
      if (tamper_for_testing != nullptr) tamper_for_testing(batches[k], outcome.result);
      outcome.compute_seconds = rays > 0 ? seconds * double(batches[k].ray_count) / double(rays)
                                         : seconds / double(end - begin);
    }
    begin = end;
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
