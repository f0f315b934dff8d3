#include "agent/point_leases.h"

#include <chrono>
#include <utility>

#include "loop/log.h"

namespace radfarm::agent {
namespace {

using loop::LogLevel;
using loop::LogLine;

std::string Describe(const protocol::LeaseRef& lease) {
  return "point lease job " + std::to_string(lease.job_id) + " piece " +
         std::to_string(lease.batch_id) + " attempt " + std::to_string(lease.attempt_id);
}

}  // namespace

PointWork PointWorkOf(const protocol::PointLeaseMsg& lease) {
  PointWork work;
  work.points.reserve(lease.points.size());
  for (const protocol::LeasedPoint& point : lease.points) {
    work.points.push_back(ReceiverPoint{point.position, point.normal});
  }
  work.seed = lease.seed;
  work.first_index = lease.first_index;
  work.near_radius = lease.near_radius;
  work.direct = lease.direct;
  work.gather.assign(lease.gather.begin(), lease.gather.end());
  work.gather_rays = lease.gather_rays;
  work.start_sections = lease.start_sections;
  work.start_patches = lease.start_patches;
  work.score_elements = lease.score_elements;
  return work;
}

protocol::PointResultMsg PointResultOf(const protocol::LeaseRef& lease, PointValues values,
                                       double compute_seconds) {
  protocol::PointResultMsg result;
  result.lease = lease;
  result.near.assign(values.near.begin(), values.near.end());
  result.direct = std::move(values.direct);
  result.gathered = std::move(values.gathered);
  result.punctual = std::move(values.punctual);
  result.scores = std::move(values.scores);
  result.rays = values.rays;
  result.compute_seconds = compute_seconds;
  return result;
}

PointLeases::PointLeases(loop::WorkQueue& batches, SceneSupply& supply, std::string master,
                         Callbacks callbacks)
    : batches_(batches),
      supply_(supply),
      master_(std::move(master)),
      callbacks_(std::move(callbacks)) {}

void PointLeases::OnLease(const protocol::PointLeaseMsg& lease, bool accepting) {
  if (!accepting) {
    callbacks_.return_leases({lease.lease}, protocol::LeaseReturnReason::kDraining, "draining");
    return;
  }
  for (const auto& [id, held] : leases_) {
    if (held.lease.lease == lease.lease) {
      LogLine(LogLevel::kWarning, "agent")
          << Describe(lease.lease) << " from " << master_ << ": already held; ignored the repeat";
      return;
    }
  }
  LogLine(LogLevel::kDebug, "agent")
      << "received " << Describe(lease.lease) << ": "
      << (lease.start_sections > 0   ? std::to_string(lease.start_patches) + " start patches"
          : lease.score_elements > 0 ? std::to_string(lease.score_elements) + " score elements"
                                     : std::to_string(lease.points.size()) + " points")
      << " from " << master_ << ", point context " << protocol::HashToHex(lease.context_hash);
  const uint64_t id = next_id_++;
  leases_[id] = Held{lease, nullptr};
  if (std::shared_ptr<const PreparedContext> context = supply_.FindContext(lease.context_hash)) {
    Submit(id, context);
  } else if (Status wanted = supply_.Want(lease.context_hash, SceneSupply::Blob::kPointContext);
             !wanted) {
    ReturnOne(id, protocol::LeaseReturnReason::kFailed, wanted.error());
  }
}

void PointLeases::OnContextReady(const std::shared_ptr<const PreparedContext>& context) {
  std::vector<uint64_t> ready;
  for (const auto& [id, held] : leases_) {
    if (!held.task && held.lease.context_hash == context->hash) ready.push_back(id);
  }
  for (uint64_t id : ready) Submit(id, context);
}

void PointLeases::OnContextFailed(const protocol::SceneHash& hash,
                                  protocol::LeaseReturnReason reason, const std::string& why) {
  std::vector<protocol::LeaseRef> refs;
  std::erase_if(leases_, [&](const auto& entry) {
    const Held& held = entry.second;
    if (held.task || held.lease.context_hash != hash) return false;
    refs.push_back(held.lease.lease);
    return true;
  });
  if (refs.empty()) return;
  callbacks_.return_leases(std::move(refs), reason,
                           "point context " + protocol::HashToHex(hash) + ": " + why);
  callbacks_.on_leases_changed();
}

void PointLeases::Submit(uint64_t id, const std::shared_ptr<const PreparedContext>& context) {
  Held& held = leases_.at(id);
  // A start lease names patches of the context's scene: the master's mistake if they lie past it.
  const protocol::PointLeaseMsg& lease = held.lease;
  if (lease.start_sections > 0 &&
      lease.first_index + lease.start_patches > context->scene->patches.size()) {
    ReturnOne(id, protocol::LeaseReturnReason::kFailed,
              "start patches " + std::to_string(lease.first_index) + ".." +
                  std::to_string(lease.first_index + lease.start_patches) + " past the scene's " +
                  std::to_string(context->scene->patches.size()));
    return;
  }
  // So does a score lease's elements past the context's score work.
  if (lease.score_elements > 0 &&
      lease.first_index + lease.score_elements > context->tracer->score_elements()) {
    ReturnOne(id, protocol::LeaseReturnReason::kFailed,
              "score elements " + std::to_string(lease.first_index) + ".." +
                  std::to_string(lease.first_index + lease.score_elements) +
                  " past the point context's " + std::to_string(context->tracer->score_elements()));
    return;
  }
  auto task = std::make_shared<std::atomic<int>>(kWaiting);
  Status submitted = batches_.Submit(
      [task, context, work = PointWorkOf(held.lease)]() -> Traced {
        Traced traced;
        int waiting = kWaiting;
        if (!task->compare_exchange_strong(waiting, kRunning)) {
          traced.skipped = true;
          return traced;
        }
        const auto start = std::chrono::steady_clock::now();
        // One thread per task, as batches: the workers are the agent's threads.
        traced.values = context->tracer->Trace(work, 0, work.size(), 1);
        traced.compute_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return traced;
      },
      [this, id](Result<Traced> traced) { OnTraced(id, std::move(traced)); });
  if (!submitted) {
    ReturnOne(id, protocol::LeaseReturnReason::kFailed, submitted.error());
    return;
  }
  held.task = std::move(task);
  ++tasks_in_flight_;
}

void PointLeases::OnTraced(uint64_t id, Result<Traced> traced) {
  --tasks_in_flight_;
  auto found = leases_.find(id);
  if (found == leases_.end()) {
    if (traced && !traced->skipped) {
      LogLine(LogLevel::kDebug, "agent") << "discarded the result of a point lease no longer held";
    }
    return;
  }
  if (!traced) {
    LogLine(LogLevel::kError, "agent")
        << Describe(found->second.lease.lease) << ": tracing failed: " << traced.error();
    ReturnOne(id, protocol::LeaseReturnReason::kFailed, traced.error());
    return;
  }
  const protocol::LeaseRef ref = found->second.lease.lease;
  const protocol::PointLeaseMsg& leased = found->second.lease;
  const size_t items = leased.start_sections > 0   ? leased.start_patches
                       : leased.score_elements > 0 ? leased.score_elements
                                                   : leased.points.size();
  const char* unit = leased.start_sections > 0   ? " start patches, "
                     : leased.score_elements > 0 ? " score elements, "
                                                 : " points, ";
  leases_.erase(found);
  const protocol::PointResultMsg result =
      PointResultOf(ref, std::move(traced->values), traced->compute_seconds);
  if (Status sent = callbacks_.send(result); !sent) {
    // No connection: the master requeues the lease when it notices.
    LogLine(LogLevel::kError, "agent") << "cannot send the result of " << Describe(ref) << " to "
                                       << master_ << ": " << sent.error();
  } else {
    LogLine(LogLevel::kDebug, "agent") << "result of " << Describe(ref) << " (" << items << unit
                                       << result.rays << " rays) sent to " << master_;
  }
  callbacks_.on_leases_changed();
}

size_t PointLeases::Revoke(const std::vector<protocol::LeaseRef>& refs) {
  size_t dropped = 0;
  for (const protocol::LeaseRef& ref : refs) {
    for (auto it = leases_.begin(); it != leases_.end(); ++it) {
      if (it->second.lease.lease != ref) continue;
      int waiting = kWaiting;
      // Running or done: its result still goes out, and the first valid one wins.
      if (it->second.task && !it->second.task->compare_exchange_strong(waiting, kDropped)) break;
      leases_.erase(it);
      ++dropped;
      break;
    }
  }
  if (dropped > 0) {
    LogLine(LogLevel::kDebug, "agent")
        << master_ << " took back " << dropped << " of our point leases not started yet";
    callbacks_.on_leases_changed();
  }
  return dropped;
}

size_t PointLeases::Cancel(uint64_t job_id) {
  std::vector<uint64_t> ids;
  for (const auto& [id, held] : leases_) {
    if (held.lease.lease.job_id == job_id) ids.push_back(id);
  }
  for (uint64_t id : ids) Forget(id);
  if (!ids.empty()) callbacks_.on_leases_changed();
  return ids.size();
}

std::vector<protocol::LeaseRef> PointLeases::TakeAll() {
  std::vector<protocol::LeaseRef> refs;
  for (const auto& [id, held] : leases_) refs.push_back(held.lease.lease);
  std::vector<uint64_t> ids;
  for (const auto& entry : leases_) ids.push_back(entry.first);
  for (uint64_t id : ids) Forget(id);
  return refs;
}

void PointLeases::Forget(uint64_t id) {
  auto found = leases_.find(id);
  if (found == leases_.end()) return;
  if (found->second.task) {
    int waiting = kWaiting;
    found->second.task->compare_exchange_strong(waiting, kDropped);
  }
  leases_.erase(found);
}

void PointLeases::ReturnOne(uint64_t id, protocol::LeaseReturnReason reason,
                            const std::string& why) {
  auto found = leases_.find(id);
  const protocol::LeaseRef ref = found->second.lease.lease;
  leases_.erase(found);
  callbacks_.return_leases({ref}, reason, why);
  callbacks_.on_leases_changed();
}

}  // namespace radfarm::agent
