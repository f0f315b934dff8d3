// LeaseBook: the leases the agent holds on its current connection, each with its stage:
//
//   kAwaitingScene --scene ready: MarkQueued()--> kQueued --PopQueued(): a worker is free-->
//   kRunning kRunning --computed, with --slowdown > 1--> kHolding (a loop timer holds the result)
//   any stage --result sent, lease returned, Cancel (RemoveJob) or disconnect (RemoveAll)--> gone
//
// Each lease gets a local id that is never reused, so a worker's result that comes back after its
// lease was cancelled or dropped finds nothing under its id and is discarded. Loop thread only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "agent/prepared_scene.h"
#include "loop/timer.h"
#include "protocol/messages.h"

namespace radfarm::agent {

enum class LeaseStage { kAwaitingScene, kQueued, kRunning, kHolding };

struct HeldLease {
  uint64_t id = 0;
  protocol::BatchAssignmentMsg assignment;
  LeaseStage stage = LeaseStage::kAwaitingScene;
  std::shared_ptr<const PreparedScene> scene;      // set from kQueued on
  std::unique_ptr<loop::Timer> hold_timer;         // kHolding
  std::optional<protocol::BatchResultMsg> result;  // kHolding
};

class LeaseBook {
 public:
  // Records a new lease (kAwaitingScene).
  HeldLease& Add(const protocol::BatchAssignmentMsg& assignment);
  HeldLease* Find(uint64_t id);
  bool Holds(const protocol::LeaseRef& lease) const;

  // kAwaitingScene -> kQueued, at the back of the run queue.
  void MarkQueued(HeldLease& lease, std::shared_ptr<const PreparedScene> scene);
  // The oldest queued lease, now kRunning; null when none is queued.
  HeldLease* PopQueued();

  // The ids of the leases waiting for scene `hash`, oldest first.
  std::vector<uint64_t> AwaitingScene(const protocol::SceneHash& hash) const;

  // Removes one lease and returns its reference.
  protocol::LeaseRef Remove(uint64_t id);
  // Removes every lease of a job (Cancel); returns them, oldest first.
  std::vector<protocol::LeaseRef> RemoveJob(uint64_t job_id);
  // Removes every lease (drain, shutdown, disconnect); returns them, oldest first.
  std::vector<protocol::LeaseRef> RemoveAll();

  size_t size() const { return leases_.size(); }
  bool empty() const { return leases_.empty(); }
  size_t CountInStage(LeaseStage stage) const;

 private:
  uint64_t next_id_ = 1;
  std::map<uint64_t, HeldLease> leases_;  // by id: oldest first
  std::deque<uint64_t> queue_;            // kQueued ids; removed leases are skipped when popped
};

}  // namespace radfarm::agent
