// LeaseWorker: the agent's work side. It takes the master's LeaseAssignments (many batches a
// frame), gets their scenes (SceneSupply), runs their batches on the batch work queue, one
// BatchTracer per worker (TracerPool), and answers each frame's batches together in one
// LeaseResult once all are computed (after --slowdown's hold), or returns a batch in a LeaseReturn
// when it cannot run it. A LeaseRevoke drops the named batches not started yet (another agent
// took them over); the frame is then answered without them. LeaseBook has each batch's stages.
// Point leases (pieces of a job's display) are PointLeases' (agent/point_leases.h); Revoke,
// Cancel, ReturnAll, DropAll, held() and busy() cover them too.
//
// The runner keeps at most `threads` tasks on the work queue, each a run of queued batches of about
// an equal share of the queued rays (at most kChunkRays), and the rest in its own queue, so a
// Cancel or LeaseRevoke drops the queued ones at once; the result of a running batch whose lease
// is gone (cancelled, returned, connection lost) is discarded when it comes back. Batches are
// computed exactly as BatchTracer::Run computes them locally: nothing here changes a result.
//
// Loop thread only; batches run on the work queue's workers, scene work on the I/O queue's.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "agent/agent_settings.h"
#include "agent/lease_book.h"
#include "agent/point_leases.h"
#include "agent/sampler_cache.h"
#include "agent/scene_store.h"
#include "agent/scene_supply.h"
#include "agent/throughput_meter.h"
#include "agent/tracer_pool.h"
#include "loop/event_loop.h"
#include "loop/timer.h"
#include "loop/work_queue.h"
#include "protocol/messages.h"

namespace radfarm::agent {

class LeaseWorker {
 public:
  struct Callbacks {
    // Sends a message to the master; fails when there is no connection.
    std::function<Status(const protocol::Message& message)> send;
    // The connection's protocol version, which sizes the result frames. Unset: kProtocolVersion.
    std::function<uint16_t()> protocol_version;
    // The leases held changed (one finished, was returned or dropped): drain and idle checks.
    std::function<void()> on_leases_changed;
  };

  // The queues must outlive the runner's last delivered result: destroy them first.
  LeaseWorker(loop::EventLoop& loop, const AgentSettings& settings, loop::WorkQueue& batches,
              loop::WorkQueue& io, std::optional<SceneStore> store, std::string master,
              Callbacks callbacks);

  // A new lease frame. When not `accepting` (draining) its batches are returned at once (reason
  // Draining).
  void OnLease(const protocol::LeaseAssignmentMsg& lease, bool accepting);
  // A new point lease (PointLeases::OnLease).
  void OnPointLease(const protocol::PointLeaseMsg& lease, bool accepting);
  // Drops the named batches and point leases that have not started; returns how many were dropped.
  size_t Revoke(const protocol::LeaseRevokeMsg& revoke);
  // Drops the job's leases, queued and running; returns how many were held.
  size_t Cancel(uint64_t job_id);
  // Returns every lease held to the master (one LeaseReturn per 65536) with `reason`.
  void ReturnAll(protocol::LeaseReturnReason reason, const std::string& why);
  // The connection is gone: forgets every lease (the master requeues them) and the fetches.
  size_t DropAll();

  SceneSupply& scenes() { return *scenes_; }
  size_t held() const { return book_.size() + points_->held(); }
  // Batches and point leases submitted to the workers and scene work on the I/O queue, not yet
  // delivered back.
  bool busy() const { return tasks_in_flight_ > 0 || points_->busy() > 0 || scenes_->busy() > 0; }
  double RaysPerSecond() const { return meter_.RaysPerSecond(); }

 private:
  void OnSceneReady(const std::shared_ptr<const PreparedScene>& scene);
  void OnSceneFailed(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                     const std::string& why);
  // A batch must lie inside its shot where the sampler fixes the shot's size (the grid).
  Status CheckRayRange(const protocol::AssignedBatch& assignment);
  // kAwaitingScene -> kQueued once its scene is ready, after checking the patch count.
  void Enqueue(HeldLease& lease, const std::shared_ptr<const PreparedScene>& scene);
  // Starts queued leases while a worker is free.
  void Dispatch();
  void OnBatchesDone(const std::vector<uint64_t>& ids, Result<std::vector<BatchOutcome>> outcomes);
  // Once every batch of the frame still held is computed: holds (--slowdown) and sends them.
  // Before that, sends the done ones early once they fill a result frame.
  void MaybeFinishGroup(uint64_t group);
  void SendGroup(uint64_t group);
  // Sends the group's done results in frames and forgets them; `finish`: and the group.
  void SendDone(uint64_t group, bool finish);
  uint16_t ProtocolVersion() const;
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
  std::unique_ptr<PointLeases> points_;
  size_t tasks_in_flight_ = 0;

  // One lease frame's batches (LeaseBook ids), answered together, except that results filling a
  // frame go out as soon as they are done: a big scene's long batches have results of hundreds
  // of KB, which held for a whole lease would pile up in the agent's memory.
  struct Group {
    uint64_t job_id = 0;
    std::vector<uint64_t> ids;
    std::optional<std::chrono::steady_clock::time_point> started;  // its first batch began
    std::unique_ptr<loop::Timer> hold_timer;                       // --slowdown
  };
  std::map<uint64_t, Group> groups_;
  uint64_t next_group_ = 1;
};

// "job 3 batch 17 attempt 0"; for several leases the count and the first few.
std::string DescribeLeases(const std::vector<protocol::LeaseRef>& leases);

}  // namespace radfarm::agent
