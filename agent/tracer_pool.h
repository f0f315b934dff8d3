// TracerPool: the BatchTracers of the batch worker threads. A BatchTracer keeps a scratch array as
// long as its scene has patches, so workers reuse runners rather than build one per batch: each
// batch borrows a free runner, preferring one already made for its scene and sampler, and gives it
// back when done. At most one runner exists per batch running at once, so the pool never holds
// more runners than there are worker threads. A free runner keeps its scene and sampler alive until
// a batch of another pair rebinds it.
//
// Threads: Run() from any worker thread; the pool's lock is held only to borrow and return.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "agent/prepared_scene.h"
#include "core/batch.h"
#include "core/batch_tracer.h"
#include "core/ray_sampler.h"

namespace radfarm::agent {

// A computed batch and how long it took.
struct BatchOutcome {
  BatchResult result;
  double compute_seconds = 0;
};

// Tests only (tests/farm's radfarm-lying-agent): a function applied to every batch result before
// it is sent, to make an agent that computes correctly and then lies. Set it before the agent
// starts; the shipped radfarm-agent never sets it (no flag or variable reaches it).
using ResultTamper = void (*)(const Batch& batch, BatchResult& result);
void SetResultTamperForTesting(ResultTamper tamper);

class TracerPool {
 public:
  BatchOutcome Run(const std::shared_ptr<const PreparedScene>& scene,
                   const std::shared_ptr<const RaySampler>& sampler, const Batch& batch);
  // Several batches of one scene and sampler, one after another on one borrowed runner: a
  // worker takes a run of a lease's small batches at once instead of one queue hand-off each.
  std::vector<BatchOutcome> RunAll(const std::shared_ptr<const PreparedScene>& scene,
                                   const std::shared_ptr<const RaySampler>& sampler,
                                   const std::vector<Batch>& batches);

 private:
  // A runner and what it is bound to (BatchTracer keeps references to both).
  struct Slot {
    std::shared_ptr<const PreparedScene> scene;
    std::shared_ptr<const RaySampler> sampler;
    std::optional<BatchTracer> runner;
  };
  std::unique_ptr<Slot> Borrow(const std::shared_ptr<const PreparedScene>& scene,
                               const std::shared_ptr<const RaySampler>& sampler);
  void GiveBack(std::unique_ptr<Slot> slot);

  std::mutex mutex_;
  std::vector<std::unique_ptr<Slot>> free_;  // guarded by mutex_
};

}  // namespace radfarm::agent
