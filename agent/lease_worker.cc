#include "agent/lease_worker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "loop/log.h"
#include "protocol/batch_convert.h"
#include "protocol/limits.h"
#include "protocol/scene_transfer.h"

namespace radfarm::agent {
namespace {

using loop::LogLevel;
using loop::LogLine;

std::string Describe(const protocol::LeaseRef& lease) {
  return "job " + std::to_string(lease.job_id) + " batch " + std::to_string(lease.batch_id) +
         " attempt " + std::to_string(lease.attempt_id);
}

const char* ReasonName(protocol::LeaseReturnReason reason) {
  switch (reason) {
    case protocol::LeaseReturnReason::kDraining:
      return "Draining";
    case protocol::LeaseReturnReason::kSceneUnavailable:
      return "SceneUnavailable";
    case protocol::LeaseReturnReason::kOverloaded:
      return "Overloaded";
    case protocol::LeaseReturnReason::kFailed:
      return "Failed";
  }
  return "?";
}

}  // namespace

std::string DescribeLeases(const std::vector<protocol::LeaseRef>& leases) {
  if (leases.size() == 1) return "lease " + Describe(leases.front());
  std::ostringstream text;
  text << leases.size() << " leases";
  const size_t shown = std::min<size_t>(leases.size(), 3);
  for (size_t i = 0; i < shown; ++i) text << (i == 0 ? " (" : ", ") << Describe(leases[i]);
  if (shown > 0) text << (leases.size() > shown ? ", ...)" : ")");
  return text.str();
}

LeaseWorker::LeaseWorker(loop::EventLoop& loop, const AgentSettings& settings,
                         loop::WorkQueue& batches, loop::WorkQueue& io,
                         std::optional<SceneStore> store, std::string master, Callbacks callbacks)
    : loop_(loop),
      settings_(settings),
      batches_(batches),
      master_(std::move(master)),
      callbacks_(std::move(callbacks)),
      meter_(settings.threads, settings.slowdown) {
  SceneSupply::Callbacks scene_callbacks;
  scene_callbacks.on_ready = [this](const auto& scene) { OnSceneReady(scene); };
  scene_callbacks.on_failed = [this](const auto& hash, auto reason, const std::string& why) {
    OnSceneFailed(hash, reason, why);
  };
  scene_callbacks.send_request = [this](const protocol::SceneRequestMsg& request) {
    return callbacks_.send(request);
  };
  scenes_ = std::make_unique<SceneSupply>(io, std::move(store), master_, scene_callbacks);
}

void LeaseWorker::OnAssignment(const protocol::BatchAssignmentMsg& assignment, bool accepting) {
  if (!accepting) {
    Return({assignment.lease}, protocol::LeaseReturnReason::kDraining, "draining");
    return;
  }
  if (book_.Holds(assignment.lease)) {
    LogLine(LogLevel::kWarning, "agent") << "lease " << Describe(assignment.lease) << " from "
                                         << master_ << ": already held; ignored the repeat";
    return;
  }
  HeldLease& lease = book_.Add(assignment);
  if (Status valid = CheckRayRange(assignment); !valid) {
    ReturnOne(lease.id, protocol::LeaseReturnReason::kFailed, valid.error());
    return;
  }
  LogLine(LogLevel::kDebug, "agent")
      << "lease " << Describe(assignment.lease) << " from " << master_ << ": "
      << assignment.ray_count << " rays of shooter " << assignment.shooter << " in round "
      << assignment.round << ", scene " << protocol::HashToHex(assignment.scene_hash);
  if (std::shared_ptr<const PreparedScene> scene = scenes_->Find(assignment.scene_hash)) {
    Enqueue(lease, scene);
  } else if (Status wanted = scenes_->Want(assignment.scene_hash); !wanted) {
    ReturnOne(lease.id, protocol::LeaseReturnReason::kFailed, wanted.error());
  }
  Dispatch();
}

Status LeaseWorker::CheckRayRange(const protocol::BatchAssignmentMsg& a) {
  // The grid sampler has a fixed number of rays per shot and no ray beyond it (its tables end
  // there): such a batch is a master's bug, refused rather than run.
  const uint64_t per_shot =
      samplers_.Get(a.sampler, a.seed, a.grid_step_degrees)->FixedRaysPerShot();
  if (per_shot != 0 && (a.first_ray >= per_shot || a.ray_count > per_shot - a.first_ray)) {
    return Error{"rays [" + std::to_string(a.first_ray) + ", " +
                 std::to_string(a.first_ray + a.ray_count) + ") are beyond the grid's " +
                 std::to_string(per_shot) + " rays per shot"};
  }
  return Ok{};
}

void LeaseWorker::Enqueue(HeldLease& lease, const std::shared_ptr<const PreparedScene>& scene) {
  if (scene->patch_count() != lease.assignment.patch_count) {
    ReturnOne(lease.id, protocol::LeaseReturnReason::kFailed,
              "scene " + protocol::HashToHex(scene->hash) + " has " +
                  std::to_string(scene->patch_count()) + " patches, the assignment says " +
                  std::to_string(lease.assignment.patch_count));
    return;
  }
  book_.MarkQueued(lease, scene);
}

void LeaseWorker::OnSceneReady(const std::shared_ptr<const PreparedScene>& scene) {
  for (uint64_t id : book_.AwaitingScene(scene->hash)) Enqueue(*book_.Find(id), scene);
  Dispatch();
}

void LeaseWorker::OnSceneFailed(const protocol::SceneHash& hash, protocol::LeaseReturnReason reason,
                                const std::string& why) {
  std::vector<protocol::LeaseRef> leases;
  for (uint64_t id : book_.AwaitingScene(hash)) leases.push_back(book_.Remove(id));
  if (leases.empty()) return;
  Return(std::move(leases), reason, "scene " + protocol::HashToHex(hash) + ": " + why);
  callbacks_.on_leases_changed();
}

void LeaseWorker::Dispatch() {
  while (batches_in_flight_ < settings_.threads) {
    HeldLease* lease = book_.PopQueued();
    if (lease == nullptr) return;
    const protocol::BatchAssignmentMsg& a = lease->assignment;
    std::shared_ptr<const RaySampler> sampler =
        samplers_.Get(a.sampler, a.seed, a.grid_step_degrees);
    Status submitted = batches_.Submit(
        [runners = runners_, scene = lease->scene, sampler, batch = protocol::ToBatch(a)] {
          return runners->Run(scene, sampler, batch);
        },
        [this, id = lease->id](Result<BatchOutcome> outcome) {
          OnBatchDone(id, std::move(outcome));
        });
    if (!submitted) {
      ReturnOne(lease->id, protocol::LeaseReturnReason::kFailed, submitted.error());
      continue;
    }
    ++batches_in_flight_;
  }
}

void LeaseWorker::OnBatchDone(uint64_t id, Result<BatchOutcome> outcome) {
  --batches_in_flight_;
  HeldLease* lease = book_.Find(id);
  if (lease == nullptr) {
    LogLine(LogLevel::kDebug, "agent") << "discarded the result of a lease no longer held";
  } else if (!outcome) {
    LogLine(LogLevel::kError, "agent") << "lease " << Describe(lease->assignment.lease)
                                       << ": the batch failed: " << outcome.error();
    ReturnOne(id, protocol::LeaseReturnReason::kFailed, outcome.error());
  } else {
    meter_.Add(lease->assignment.ray_count, outcome->compute_seconds);
    lease->result = protocol::MakeBatchResult(lease->assignment.lease, outcome->result,
                                              outcome->compute_seconds);
    if (settings_.slowdown > 1) {
      // Simulates a slower machine: the result goes out (F - 1) x its compute time later.
      const double hold_ms = (settings_.slowdown - 1) * outcome->compute_seconds * 1000;
      lease->stage = LeaseStage::kHolding;
      const std::chrono::milliseconds hold(
          static_cast<int64_t>(std::min(std::ceil(hold_ms), 1e15)));
      LogLine(LogLevel::kDebug, "agent")
          << "lease " << Describe(lease->assignment.lease) << ": result held for " << hold.count()
          << " ms (--slowdown)";
      lease->hold_timer = std::make_unique<loop::Timer>(loop_);
      lease->hold_timer->Start(hold, [this, id] { SendResult(id); });
    } else {
      SendResult(id);
    }
  }
  Dispatch();
}

void LeaseWorker::SendResult(uint64_t id) {
  HeldLease* lease = book_.Find(id);
  if (lease == nullptr) return;
  if (Status sent = callbacks_.send(*lease->result); !sent) {
    LogLine(LogLevel::kError, "agent")
        << "lease " << Describe(lease->assignment.lease) << ": cannot send the result to "
        << master_ << ": " << sent.error();
    ReturnOne(id, protocol::LeaseReturnReason::kFailed, sent.error());
    return;
  }
  LogLine(LogLevel::kDebug, "agent")
      << "lease " << Describe(lease->assignment.lease) << ": result sent to " << master_ << " ("
      << lease->result->compute_seconds << " s)";
  book_.Remove(id);
  callbacks_.on_leases_changed();
}

size_t LeaseWorker::Cancel(uint64_t job_id) {
  const std::vector<protocol::LeaseRef> dropped = book_.RemoveJob(job_id);
  if (!dropped.empty()) callbacks_.on_leases_changed();
  return dropped.size();
}

void LeaseWorker::ReturnAll(protocol::LeaseReturnReason reason, const std::string& why) {
  std::vector<protocol::LeaseRef> leases = book_.RemoveAll();
  if (leases.empty()) return;
  Return(std::move(leases), reason, why);
  callbacks_.on_leases_changed();
}

size_t LeaseWorker::DropAll() {
  scenes_->OnDisconnected();
  return book_.RemoveAll().size();
}

void LeaseWorker::ReturnOne(uint64_t id, protocol::LeaseReturnReason reason,
                            const std::string& why) {
  Return({book_.Remove(id)}, reason, why);
  callbacks_.on_leases_changed();
}

void LeaseWorker::Return(std::vector<protocol::LeaseRef> leases, protocol::LeaseReturnReason reason,
                         const std::string& why) {
  LogLine(LogLevel::kInfo, "agent") << "returning " << DescribeLeases(leases) << " to " << master_
                                    << " (" << ReasonName(reason) << "): " << why;
  for (size_t first = 0; first < leases.size(); first += protocol::kMaxLeaseReturnEntries) {
    const size_t last = std::min(leases.size(), first + protocol::kMaxLeaseReturnEntries);
    protocol::LeaseReturnMsg message;
    message.leases.assign(leases.begin() + static_cast<ptrdiff_t>(first),
                          leases.begin() + static_cast<ptrdiff_t>(last));
    message.reason = reason;
    if (Status sent = callbacks_.send(message); !sent) {
      LogLine(LogLevel::kWarning, "agent")
          << "cannot return " << DescribeLeases(message.leases) << " to " << master_ << ": "
          << sent.error() << " (the master requeues them when the connection ends)";
      return;
    }
  }
}

}  // namespace radfarm::agent
