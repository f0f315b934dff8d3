#include "agent/lease_book.h"

namespace radfarm::agent {

HeldLease& LeaseBook::Add(const protocol::BatchAssignmentMsg& assignment) {
  const uint64_t id = next_id_++;
  HeldLease& lease = leases_[id];
  lease.id = id;
  lease.assignment = assignment;
  return lease;
}

HeldLease* LeaseBook::Find(uint64_t id) {
  auto found = leases_.find(id);
  return found == leases_.end() ? nullptr : &found->second;
}

bool LeaseBook::Holds(const protocol::LeaseRef& lease) const {
  for (const auto& [id, held] : leases_) {
    if (held.assignment.lease == lease) return true;
  }
  return false;
}

void LeaseBook::MarkQueued(HeldLease& lease, std::shared_ptr<const PreparedScene> scene) {
  lease.stage = LeaseStage::kQueued;
  lease.scene = std::move(scene);
  queue_.push_back(lease.id);
}

HeldLease* LeaseBook::PopQueued() {
  while (!queue_.empty()) {
    HeldLease* lease = Find(queue_.front());
    queue_.pop_front();
    if (lease != nullptr && lease->stage == LeaseStage::kQueued) {
      lease->stage = LeaseStage::kRunning;
      return lease;
    }
  }
  return nullptr;
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
  leases_.erase(found);
  return ref;
}

std::vector<protocol::LeaseRef> LeaseBook::RemoveJob(uint64_t job_id) {
  std::vector<protocol::LeaseRef> removed;
  for (auto it = leases_.begin(); it != leases_.end();) {
    if (it->second.assignment.lease.job_id == job_id) {
      removed.push_back(it->second.assignment.lease);
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
  queue_.clear();
  return removed;
}

size_t LeaseBook::CountInStage(LeaseStage stage) const {
  size_t count = 0;
  for (const auto& [id, held] : leases_) count += held.stage == stage ? 1 : 0;
  return count;
}

}  // namespace radfarm::agent
