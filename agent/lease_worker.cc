#include "agent/lease_worker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/batch.h"
#include "loop/log.h"
#include "protocol/batch_convert.h"
#include "protocol/frame_codec.h"
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
  scene_callbacks.on_context_ready = [this](const auto& context) {
    points_->OnContextReady(context);
  };
  scene_callbacks.on_failed = [this](const auto& hash, auto reason, const std::string& why) {
    OnSceneFailed(hash, reason, why);
    points_->OnContextFailed(hash, reason, why);
  };
  scene_callbacks.send_request = [this](const protocol::SceneRequestMsg& request) {
    return callbacks_.send(request);
  };
  scenes_ = std::make_unique<SceneSupply>(io, std::move(store), master_, scene_callbacks);
  PointLeases::Callbacks point_callbacks;
  point_callbacks.send = [this](const protocol::Message& message) {
    return callbacks_.send(message);
  };
  point_callbacks.return_leases = [this](std::vector<protocol::LeaseRef> leases, auto reason,
                                         const std::string& why) {
    Return(std::move(leases), reason, why);
  };
  point_callbacks.on_leases_changed = [this] { callbacks_.on_leases_changed(); };
  points_ = std::make_unique<PointLeases>(batches, *scenes_, master_, point_callbacks);
}

void LeaseWorker::OnPointLease(const protocol::PointLeaseMsg& lease, bool accepting) {
  points_->OnLease(lease, accepting);
}

void LeaseWorker::OnLease(const protocol::LeaseAssignmentMsg& frame, bool accepting) {
  if (!accepting) {
    std::vector<protocol::LeaseRef> leases;
    for (const protocol::LeaseBatch& b : frame.batches) {
      leases.push_back({frame.job_id, b.batch_id, b.attempt_id});
    }
    Return(std::move(leases), protocol::LeaseReturnReason::kDraining, "draining");
    return;
  }
  const uint64_t group_id = next_group_++;
  {
    std::vector<protocol::LeaseRef> refs;
    for (size_t k = 0; k < std::min<size_t>(frame.batches.size(), 4); ++k) {
      refs.push_back({frame.job_id, frame.batches[k].batch_id, frame.batches[k].attempt_id});
    }
    LogLine(LogLevel::kDebug, "agent")
        << "received " << frame.batches.size() << " batches of "
        << (frame.round == kGatherRound ? std::string("the final gather")
                                        : "round " + std::to_string(ShownRound(frame.round)))
        << ": " << DescribeLeases(refs) << " from " << master_ << ", scene "
        << protocol::HashToHex(frame.scene_hash);
  }
  std::vector<uint64_t> ids;
  for (size_t k = 0; k < frame.batches.size(); ++k) {
    const protocol::AssignedBatch assignment = protocol::BatchOf(frame, k);
    if (book_.Holds(assignment.lease)) {
      LogLine(LogLevel::kWarning, "agent") << "lease " << Describe(assignment.lease) << " from "
                                           << master_ << ": already held; ignored the repeat";
      continue;
    }
    ids.push_back(book_.Add(assignment, group_id).id);
  }
  groups_[group_id] = Group{frame.job_id, ids, std::nullopt, nullptr};
  // The group is complete before any batch can leave it (ReturnOne may end it).
  std::vector<uint64_t> added;
  for (uint64_t id : ids) {
    if (Status valid = CheckRayRange(book_.Find(id)->assignment); !valid) {
      ReturnOne(id, protocol::LeaseReturnReason::kFailed, valid.error());
      continue;
    }
    added.push_back(id);
  }
  if (std::shared_ptr<const PreparedScene> scene = scenes_->Find(frame.scene_hash)) {
    for (uint64_t id : added) {
      if (HeldLease* lease = book_.Find(id)) Enqueue(*lease, scene);
    }
  } else if (!added.empty()) {
    if (Status wanted = scenes_->Want(frame.scene_hash); !wanted) {
      for (uint64_t id : added) {
        if (book_.Find(id) != nullptr)
          ReturnOne(id, protocol::LeaseReturnReason::kFailed, wanted.error());
      }
    }
  }
  MaybeFinishGroup(group_id);  // every batch refused: nothing left to wait for
  Dispatch();
}

size_t LeaseWorker::Revoke(const protocol::LeaseRevokeMsg& revoke) {
  const size_t points = points_->Revoke(revoke.leases);
  std::vector<uint64_t> touched;
  size_t dropped = 0;
  for (const protocol::LeaseRef& ref : revoke.leases) {
    HeldLease* lease = book_.Find(ref);
    if (lease == nullptr) continue;
    if (lease->stage != LeaseStage::kQueued && lease->stage != LeaseStage::kAwaitingScene) {
      continue;  // running or done: its result still goes out, and the first valid one wins
    }
    touched.push_back(lease->group);
    book_.Remove(lease->id);
    ++dropped;
  }
  for (uint64_t group : touched) MaybeFinishGroup(group);
  if (dropped > 0) {
    LogLine(LogLevel::kDebug, "agent")
        << master_ << " took back " << dropped << " of our batches not started yet";
    callbacks_.on_leases_changed();
  }
  return dropped + points;
}

Status LeaseWorker::CheckRayRange(const protocol::AssignedBatch& a) {
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
  std::vector<uint64_t> touched;
  for (uint64_t id : book_.AwaitingScene(hash)) {
    touched.push_back(book_.Find(id)->group);
    leases.push_back(book_.Remove(id));
  }
  if (leases.empty()) return;
  Return(std::move(leases), reason, "scene " + protocol::HashToHex(hash) + ": " + why);
  for (uint64_t group : touched) MaybeFinishGroup(group);
  callbacks_.on_leases_changed();
}

namespace {

// A worker task runs queued batches up to about this many rays (a few ms on one thread): big
// enough that the queue hand-off is noise, small enough that the threads share a lease evenly.
constexpr uint64_t kChunkRays = 32768;

}  // namespace

void LeaseWorker::Dispatch() {
  while (tasks_in_flight_ < settings_.threads) {
    HeldLease* first = book_.FrontQueued();
    if (first == nullptr) return;
    const std::shared_ptr<const PreparedScene> scene = first->scene;
    const protocol::AssignedBatch& a = first->assignment;
    std::shared_ptr<const RaySampler> sampler =
        samplers_.Get(a.sampler, a.seed, a.grid_step_degrees);
    // An equal share of what is queued for each thread, so the last batches of a lease do not
    // all land on one worker.
    const uint64_t share =
        std::clamp<uint64_t>(book_.queued_rays() / std::max(1u, settings_.threads), 1, kChunkRays);
    std::vector<uint64_t> ids;
    std::vector<Batch> batches;
    uint64_t rays = 0;
    while (HeldLease* next = book_.FrontQueued()) {
      const protocol::AssignedBatch& n = next->assignment;
      if (!ids.empty() && (rays >= share || next->scene != scene ||
                           samplers_.Get(n.sampler, n.seed, n.grid_step_degrees) != sampler)) {
        break;
      }
      book_.PopQueued();
      ids.push_back(next->id);
      batches.push_back(protocol::ToBatch(n));
      rays += n.ray_count;
      Group& group = groups_[next->group];
      if (!group.started) group.started = std::chrono::steady_clock::now();
    }
    Status submitted = batches_.Submit(
        [runners = runners_, scene, sampler, batches = std::move(batches)] {
          return runners->RunAll(scene, sampler, batches);
        },
        [this, ids](Result<std::vector<BatchOutcome>> outcomes) {
          OnBatchesDone(ids, std::move(outcomes));
        });
    if (!submitted) {
      for (uint64_t id : ids)
        ReturnOne(id, protocol::LeaseReturnReason::kFailed, submitted.error());
      continue;
    }
    ++tasks_in_flight_;
  }
}

void LeaseWorker::OnBatchesDone(const std::vector<uint64_t>& ids,
                                Result<std::vector<BatchOutcome>> outcomes) {
  --tasks_in_flight_;
  std::vector<uint64_t> touched;
  const uint16_t version = ProtocolVersion();  // a lease lives on one connection
  for (size_t k = 0; k < ids.size(); ++k) {
    HeldLease* lease = book_.Find(ids[k]);
    if (lease == nullptr) {
      LogLine(LogLevel::kDebug, "agent") << "discarded the result of a lease no longer held";
      continue;
    }
    touched.push_back(lease->group);
    if (!outcomes) {
      LogLine(LogLevel::kError, "agent") << "lease " << Describe(lease->assignment.lease)
                                         << ": the batch failed: " << outcomes.error();
      ReturnOne(ids[k], protocol::LeaseReturnReason::kFailed, outcomes.error());
      continue;
    }
    const BatchOutcome& outcome = (*outcomes)[k];
    meter_.Add(lease->assignment.ray_count, outcome.compute_seconds);
    lease->result = protocol::MakeBatchOutcome(lease->assignment.lease, outcome.result,
                                               outcome.compute_seconds);
    lease->result_cost = protocol::ResultFrameCost(*lease->result, version);
    lease->stage = LeaseStage::kDone;
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  for (uint64_t group : touched) MaybeFinishGroup(group);
  Dispatch();
}

void LeaseWorker::MaybeFinishGroup(uint64_t group_id) {
  const auto it = groups_.find(group_id);
  if (it == groups_.end()) return;
  Group& group = it->second;
  if (group.hold_timer) return;  // already held, on its way out
  bool any = false;
  bool all_done = true;
  size_t done_bytes = 0;
  for (uint64_t id : group.ids) {
    const HeldLease* lease = book_.Find(id);
    if (lease == nullptr) continue;
    if (lease->stage != LeaseStage::kDone) {
      all_done = false;
      continue;
    }
    any = true;
    done_bytes += lease->result_cost;
  }
  if (!all_done) {
    // A frame's worth already done goes out now (not under --slowdown, which holds a frame's
    // results on purpose).
    if (settings_.slowdown <= 1 && done_bytes >= protocol::kResultFrameBytes) {
      SendDone(group_id, /*finish=*/false);
    }
    return;
  }
  if (!any) {  // every batch was returned, revoked or cancelled
    groups_.erase(it);
    return;
  }
  if (settings_.slowdown > 1 && group.started) {
    // Simulates a slower machine: the results go out (F - 1) x the frame's time later.
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - *group.started).count();
    const double hold_ms = (settings_.slowdown - 1) * seconds * 1000;
    const std::chrono::milliseconds hold(static_cast<int64_t>(std::min(std::ceil(hold_ms), 1e15)));
    LogLine(LogLevel::kDebug, "agent")
        << "lease frame of job " << group.job_id << ": result held for " << hold.count()
        << " ms (--slowdown)";
    group.hold_timer = std::make_unique<loop::Timer>(loop_);
    group.hold_timer->Start(hold, [this, group_id] { SendGroup(group_id); });
    return;
  }
  SendGroup(group_id);
}

uint16_t LeaseWorker::ProtocolVersion() const {
  return callbacks_.protocol_version ? callbacks_.protocol_version() : protocol::kProtocolVersion;
}

void LeaseWorker::SendGroup(uint64_t group_id) { SendDone(group_id, /*finish=*/true); }

void LeaseWorker::SendDone(uint64_t group_id, bool finish) {
  const auto it = groups_.find(group_id);
  if (it == groups_.end()) return;
  // Results go out in frames of at most about protocol::kResultFrameBytes (frame_codec.h).
  std::vector<uint64_t> sent_ids;
  protocol::LeaseResultMsg message;
  size_t bytes = 0;
  Status sent = Ok{};
  auto flush = [&] {
    if (message.results.empty() || !sent) return;
    sent = callbacks_.send(message);
    message.results.clear();
    bytes = 0;
  };
  for (uint64_t id : it->second.ids) {
    HeldLease* lease = book_.Find(id);
    if (lease == nullptr || lease->stage != LeaseStage::kDone) continue;
    const size_t cost = lease->result_cost;
    if (bytes + cost > protocol::kResultFrameBytes ||
        message.results.size() == protocol::kMaxLeaseBatches) {
      flush();
    }
    message.results.push_back(std::move(*lease->result));
    bytes += cost;
    sent_ids.push_back(id);
  }
  flush();
  if (finish) groups_.erase(it);
  if (!sent) {
    LogLine(LogLevel::kError, "agent")
        << "cannot send " << sent_ids.size() << " results to " << master_ << ": " << sent.error();
  } else {
    LogLine(LogLevel::kDebug, "agent") << sent_ids.size() << " results sent to " << master_;
  }
  // Sent or not (no connection: the master requeues them when it notices), they are done here.
  for (uint64_t id : sent_ids) book_.Remove(id);
  callbacks_.on_leases_changed();
}

size_t LeaseWorker::Cancel(uint64_t job_id) {
  const std::vector<protocol::LeaseRef> dropped = book_.RemoveJob(job_id);
  std::erase_if(groups_, [&](const auto& entry) { return entry.second.job_id == job_id; });
  if (!dropped.empty()) callbacks_.on_leases_changed();
  return dropped.size() + points_->Cancel(job_id);
}

void LeaseWorker::ReturnAll(protocol::LeaseReturnReason reason, const std::string& why) {
  std::vector<protocol::LeaseRef> leases = book_.RemoveAll();
  groups_.clear();
  for (const protocol::LeaseRef& ref : points_->TakeAll()) leases.push_back(ref);
  if (leases.empty()) return;
  Return(std::move(leases), reason, why);
  callbacks_.on_leases_changed();
}

size_t LeaseWorker::DropAll() {
  scenes_->OnDisconnected();
  groups_.clear();
  return book_.RemoveAll().size() + points_->TakeAll().size();
}

void LeaseWorker::ReturnOne(uint64_t id, protocol::LeaseReturnReason reason,
                            const std::string& why) {
  const uint64_t group = book_.Find(id)->group;
  Return({book_.Remove(id)}, reason, why);
  MaybeFinishGroup(group);  // the frame's other batches may all be done
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
