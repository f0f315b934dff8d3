// LeaseBook: the leases (one batch each) the agent holds on its current connection, each with its
// stage and the lease frame (group) it came in:
//
//   kAwaitingScene --scene ready: MarkQueued()--> kQueued --PopQueued(): a worker is free-->
//   kRunning --computed--> kDone (its result waits for the other batches of its frame, and for
//   --slowdown's hold)
//   any stage --frame's results sent, lease returned, Cancel (RemoveJob), revoked before it ran,
//   or disconnect (RemoveAll)--> gone
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
#include <tuple>
#include <vector>

#include "agent/prepared_scene.h"
#include "protocol/messages.h"

namespace radfarm::agent {

enum class LeaseStage { kAwaitingScene, kQueued, kRunning, kDone };

struct HeldLease {
  uint64_t id = 0;
  uint64_t group = 0;  // the lease frame it came in (LeaseWorker answers a frame at once)
  protocol::AssignedBatch assignment;
  LeaseStage stage = LeaseStage::kAwaitingScene;
  std::shared_ptr<const PreparedScene> scene;    // set from kQueued on
  std::optional<protocol::BatchOutcome> result;  // kDone
  size_t result_cost = 0;  // kDone: its share of a LeaseResult frame (protocol::ResultFrameCost)
};

class LeaseBook {
 public:
  // Records a new lease (kAwaitingScene) of lease frame `group`.
  HeldLease& Add(const protocol::AssignedBatch& assignment, uint64_t group = 0);
  HeldLease* Find(uint64_t id);
  // The lease a reference names; null when not held. O(log n).
  HeldLease* Find(const protocol::LeaseRef& lease);
  bool Holds(const protocol::LeaseRef& lease) const;

  // kAwaitingScene -> kQueued, at the back of the run queue.
  void MarkQueued(HeldLease& lease, std::shared_ptr<const PreparedScene> scene);
  // The oldest queued lease, now kRunning; null when none is queued.
  HeldLease* PopQueued();
  // The lease PopQueued would return, left queued.
  HeldLease* FrontQueued();
  // Rays of the kQueued leases.
  uint64_t queued_rays() const { return queued_rays_; }

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
  using RefKey = std::tuple<uint64_t, uint64_t, uint32_t>;  // job, batch, attempt
  static RefKey KeyOf(const protocol::LeaseRef& lease) {
    return {lease.job_id, lease.batch_id, lease.attempt_id};
  }

  uint64_t next_id_ = 1;
  std::map<uint64_t, HeldLease> leases_;  // by id: oldest first
  std::map<RefKey, uint64_t> by_ref_;     // every held lease's id by its reference
  std::deque<uint64_t> queue_;            // kQueued ids; removed leases are skipped when popped
  uint64_t queued_rays_ = 0;
};

}  // namespace radfarm::agent
