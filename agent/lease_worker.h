// LeaseWorker: the agent's work side. It takes the master's BatchAssignments, gets their scenes
// (SceneSupply), runs their batches on the batch work queue, one BatchTracer per worker
// (TracerPool), holds each result for --slowdown, and answers with a BatchResult, or returns the
// lease in a LeaseReturn when it cannot run it. LeaseBook has each lease's stages.
//
// The runner keeps at most `threads` batches on the work queue and the rest in its own queue, so
// a Cancel drops the queued ones at once; the result of a running batch whose lease is gone
// (cancelled, returned, connection lost) is discarded when it comes back. Batches are computed
// exactly as BatchTracer::Run computes them locally: nothing here changes a result.
//
// Loop thread only; batches run on the work queue's workers, scene work on the I/O queue's.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "agent/agent_settings.h"
#include "agent/lease_book.h"
#include "agent/sampler_cache.h"
#include "agent/scene_store.h"
#include "agent/scene_supply.h"
#include "agent/throughput_meter.h"
#include "agent/tracer_pool.h"
#include "loop/event_loop.h"
#include "loop/work_queue.h"
#include "protocol/messages.h"

namespace radfarm::agent {

class LeaseWorker {
 public:
  struct Callbacks {
    // Sends a message to the master; fails when there is no connection.
    std::function<Status(const protocol::Message& message)> send;
    // The leases held changed (one finished, was returned or dropped): drain and idle checks.
    std::function<void()> on_leases_changed;
  };

  // The queues must outlive the runner's last delivered result: destroy them first.
  LeaseWorker(loop::EventLoop& loop, const AgentSettings& settings, loop::WorkQueue& batches,
              loop::WorkQueue& io, std::optional<SceneStore> store, std::string master,
              Callbacks callbacks);

  // A new lease. When not `accepting` (draining) it is returned at once (reason Draining).
  void OnAssignment(const protocol::BatchAssignmentMsg& assignment, bool accepting);
  // Drops the job's leases, queued and running; returns how many were held.
  size_t Cancel(uint64_t job_id);
  // Returns every lease held to the master (one LeaseReturn per 65536) with `reason`.
  void ReturnAll(protocol::LeaseReturnReason reason, const std::string& why);
  // The connection is gone: forgets every lease (the master requeues them) and the fetches.
  size_t DropAll();

  SceneSupply& scenes() { return *scenes_; }
  size_t held() const { return book_.size(); }
  // Batches submitted to the workers and scene work on the I/O queue, not yet delivered back.
  bool busy() const { return batches_in_flight_ > 0 || scenes_->busy() > 0; }
  double RaysPerSecond() const { return meter_.RaysPerSecond(); }

 private:
  void OnSceneReady(const std::shared_ptr<const PreparedScene>& scene);
  void OnSceneFailed(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                     const std::string& why);
  // A batch must lie inside its shot where the sampler fixes the shot's size (the grid).
  Status CheckRayRange(const protocol::BatchAssignmentMsg& assignment);
  // kAwaitingScene -> kQueued once its scene is ready, after checking the patch count.
  void Enqueue(HeldLease& lease, const std::shared_ptr<const PreparedScene>& scene);
  // Starts queued leases while a worker is free.
  void Dispatch();
  void OnBatchDone(uint64_t id, Result<BatchOutcome> outcome);
  void SendResult(uint64_t id);
  void Return(std::vector<protocol::LeaseRef> leases, protocol::LeaseReturnReason reason,
              const std::string& why);
  void ReturnOne(uint64_t id, protocol::LeaseReturnReason reason, const std::string& why);

  loop::EventLoop& loop_;
  const AgentSettings& settings_;
  loop::WorkQueue& batches_;
  std::string master_;
  Callbacks callbacks_;
  LeaseBook book_;
  SamplerCache samplers_;
  std::shared_ptr<TracerPool> runners_ = std::make_shared<TracerPool>();
  ThroughputMeter meter_;
  std::unique_ptr<SceneSupply> scenes_;
  size_t batches_in_flight_ = 0;
};

// "job 3 batch 17 attempt 0"; for several leases the count and the first few.
std::string DescribeLeases(const std::vector<protocol::LeaseRef>& leases);

}  // namespace radfarm::agent
