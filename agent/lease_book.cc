#include "agent/lease_book.h"

namespace radfarm::agent {

HeldLease& LeaseBook::Add(const protocol::AssignedBatch& assignment, uint64_t group) {
  const uint64_t id = next_id_++;
  HeldLease& lease = leases_[id];
  lease.id = id;
  lease.group = group;
  lease.assignment = assignment;
  by_ref_[KeyOf(assignment.lease)] = id;
  return lease;
}

HeldLease* LeaseBook::Find(uint64_t id) {
  auto found = leases_.find(id);
  return found == leases_.end() ? nullptr : &found->second;
}

HeldLease* LeaseBook::Find(const protocol::LeaseRef& lease) {
  const auto found = by_ref_.find(KeyOf(lease));
  return found == by_ref_.end() ? nullptr : Find(found->second);
}

bool LeaseBook::Holds(const protocol::LeaseRef& lease) const {
  return by_ref_.count(KeyOf(lease)) > 0;
}

void LeaseBook::MarkQueued(HeldLease& lease, std::shared_ptr<const PreparedScene> scene) {
  lease.stage = LeaseStage::kQueued;
  lease.scene = std::move(scene);
  queue_.push_back(lease.id);
  queued_rays_ += lease.assignment.ray_count;
}

HeldLease* LeaseBook::FrontQueued() {
  while (!queue_.empty()) {
    HeldLease* lease = Find(queue_.front());
    if (lease != nullptr && lease->stage == LeaseStage::kQueued) return lease;
    queue_.pop_front();
  }
  return nullptr;
}

HeldLease* LeaseBook::PopQueued() {
  HeldLease* lease = FrontQueued();
  if (lease == nullptr) return nullptr;
  queue_.pop_front();
  lease->stage = LeaseStage::kRunning;
  queued_rays_ -= lease->assignment.ray_count;
  return lease;
}

std::vector<uint64_t> LeaseBook::AwaitingScene(const protocol::SceneHash& hash) const {
  std::vector<uint64_t> ids;
  for (const auto& [id, held] : leases_) {
    if (held.stage == LeaseStage::kAwaitingScene && held.assignment.scene_hash == hash) {
      ids.push_back(id);
    }
  }
  return ids;
}

protocol::LeaseRef LeaseBook::Remove(uint64_t id) {
  auto found = leases_.find(id);
  const protocol::LeaseRef ref = found->second.assignment.lease;
  if (found->second.stage == LeaseStage::kQueued)
    queued_rays_ -= found->second.assignment.ray_count;
  by_ref_.erase(KeyOf(ref));
  leases_.erase(found);
  return ref;
}

std::vector<protocol::LeaseRef> LeaseBook::RemoveJob(uint64_t job_id) {
  std::vector<protocol::LeaseRef> removed;
  for (auto it = leases_.begin(); it != leases_.end();) {
    if (it->second.assignment.lease.job_id == job_id) {
      removed.push_back(it->second.assignment.lease);
      if (it->second.stage == LeaseStage::kQueued) queued_rays_ -= it->second.assignment.ray_count;
      by_ref_.erase(KeyOf(it->second.assignment.lease));
      it = leases_.erase(it);
    } else {
      ++it;
    }
  }
  return removed;
}

std::vector<protocol::LeaseRef> LeaseBook::RemoveAll() {
  std::vector<protocol::LeaseRef> removed;
  for (const auto& [id, held] : leases_) removed.push_back(held.assignment.lease);
  leases_.clear();
  by_ref_.clear();
  queue_.clear();
  queued_rays_ = 0;
  return removed;
}

size_t LeaseBook::CountInStage(LeaseStage stage) const {
  size_t count = 0;
  for (const auto& [id, held] : leases_) count += held.stage == stage ? 1 : 0;
  return count;
}

}  // namespace radfarm::agent
