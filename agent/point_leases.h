// PointLeases: the agent's point leases (protocol version 6): pieces of a job's display, each
// traced against its display step's point context, which SceneSupply fetches by hash and prepares
// (a PreparedContext). Each lease is one task on the batch work queue, traced on one thread
// (PointTracer::Trace) and answered with one PointResult holding exactly TracePoints' values.
//
// A lease's way (`leases_` holds it until it ends):
//
//   OnLease --context in memory--> submitted --traced--> PointResult sent (OnTraced)
//     +--context not ready--> awaiting --OnContextReady--> submitted
//                               +--OnContextFailed--> returned (the caller's `return_leases`)
//   awaiting, or submitted and not started --Revoke--> dropped
//   any --Cancel (its job), TakeAll (returned by the caller), DropAll--> forgotten; the result of
//         a running one is discarded when it comes back, a queued one skips its tracing.
//
// Loop thread only; tracing on the batch queue's workers.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "agent/prepared_context.h"
#include "agent/scene_supply.h"
#include "base/result.h"
#include "display/point_work.h"
#include "loop/work_queue.h"
#include "protocol/messages.h"

namespace radfarm::agent {

class PointLeases {
 public:
  struct Callbacks {
    // Sends a PointResult to the master; fails when there is no connection.
    std::function<Status(const protocol::Message& message)> send;
    // Returns leases to the master in LeaseReturns, logged.
    std::function<void(std::vector<protocol::LeaseRef> leases, protocol::LeaseReturnReason reason,
                       const std::string& why)>
        return_leases;
    // The leases held changed (one finished, was returned or dropped).
    std::function<void()> on_leases_changed;
  };

  // `batches` and `supply` must outlive this object's last delivered result.
  PointLeases(loop::WorkQueue& batches, SceneSupply& supply, std::string master,
              Callbacks callbacks);

  // A new point lease. When not `accepting` (draining) it is returned at once (reason Draining).
  void OnLease(const protocol::PointLeaseMsg& lease, bool accepting);
  void OnContextReady(const std::shared_ptr<const PreparedContext>& context);
  void OnContextFailed(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                       const std::string& why);
  // Drops the named leases that have not started; returns how many were dropped.
  size_t Revoke(const std::vector<protocol::LeaseRef>& refs);
  // Drops the job's leases, awaiting, queued and running; returns how many were held.
  size_t Cancel(uint64_t job_id);
  // Forgets every lease and gives their refs (to return them, or not when the connection is gone).
  std::vector<protocol::LeaseRef> TakeAll();

  size_t held() const { return leases_.size(); }
  // Tasks submitted to the workers, not yet delivered back.
  size_t busy() const { return tasks_in_flight_; }

 private:
  // A task's state, shared with it: a lease dropped before its task starts skips the tracing.
  enum TaskState : int { kWaiting, kRunning, kDropped };
  struct Held {
    protocol::PointLeaseMsg lease;
    std::shared_ptr<std::atomic<int>> task;  // null until submitted
  };
  // What a task gives back.
  struct Traced {
    bool skipped = false;  // dropped before it started
    PointValues values;
    double compute_seconds = 0;
  };

  void Submit(uint64_t id, const std::shared_ptr<const PreparedContext>& context);
  void OnTraced(uint64_t id, Result<Traced> traced);
  // Drops `id` from the book and stops its task if not started.
  void Forget(uint64_t id);
  void ReturnOne(uint64_t id, protocol::LeaseReturnReason reason, const std::string& why);

  loop::WorkQueue& batches_;
  SceneSupply& supply_;
  std::string master_;
  Callbacks callbacks_;
  std::map<uint64_t, Held> leases_;  // by an id of ours: a ref may come again once returned
  uint64_t next_id_ = 1;
  size_t tasks_in_flight_ = 0;
};

// The piece of display work a lease names, as TracePoints takes it.
PointWork PointWorkOf(const protocol::PointLeaseMsg& lease);
// The answer to `lease`: `values` exactly, near as 0/1 bytes.
protocol::PointResultMsg PointResultOf(const protocol::LeaseRef& lease, PointValues values,
                                       double compute_seconds);

}  // namespace radfarm::agent
