#include "daemon/jobs/display_pieces.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace radfarm::daemon {

DisplayPieces::DisplayPieces(uint32_t step, size_t points, size_t piece_points,
                             std::chrono::milliseconds lease_time)
    : step_(step), lease_time_(lease_time) {
  piece_points = std::max<size_t>(1, piece_points);
  for (size_t begin = 0; begin < points; begin += piece_points) {
    Slot slot;
    slot.begin = begin;
    slot.end = std::min(points, begin + piece_points);
    queue_.push_back(static_cast<uint32_t>(slots_.size()));
    slots_.push_back(std::move(slot));
  }
}

std::optional<uint32_t> DisplayPieces::IndexOf(uint64_t piece_id) const {
  if (static_cast<uint32_t>(piece_id >> 32) != step_) return std::nullopt;
  const uint64_t index = piece_id & 0xffffffffu;
  if (index >= slots_.size()) return std::nullopt;
  return static_cast<uint32_t>(index);
}

std::optional<std::pair<size_t, size_t>> DisplayPieces::PointsOf(uint64_t piece_id) const {
  const std::optional<uint32_t> index = IndexOf(piece_id);
  if (!index) return std::nullopt;
  return std::make_pair(slots_[*index].begin, slots_[*index].end);
}

PieceLease DisplayPieces::Issue(uint32_t index, scheduler::AgentId agent,
                                scheduler::TimePoint now) {
  Slot& slot = slots_[index];
  slot.queued = false;
  const uint32_t attempt = next_attempt_++;
  const scheduler::TimePoint deadline = now + lease_time_;
  slot.live[attempt] = {agent, deadline};
  const uint64_t id = (uint64_t{step_} << 32) | index;
  held_[agent][id] = attempt;
  return {id, attempt, slot.begin, slot.end, deadline};
}

std::optional<PieceLease> DisplayPieces::Next(scheduler::AgentId agent, scheduler::TimePoint now) {
  while (!queue_.empty()) {
    const uint32_t index = queue_.front();
    queue_.pop_front();
    const Slot& slot = slots_[index];
    if (slot.queued && !slot.values) return Issue(index, agent, now);
  }
  // The queue is empty: a piece whose every lease is overdue goes to another agent as well.
  const auto& mine = held_[agent];
  for (uint32_t index = 0; index < slots_.size(); ++index) {
    const Slot& slot = slots_[index];
    if (slot.values || slot.live.empty()) continue;
    if (mine.count((uint64_t{step_} << 32) | index)) continue;
    const bool overdue = std::all_of(slot.live.begin(), slot.live.end(),
                                     [&](const auto& live) { return live.second.second <= now; });
    if (overdue) return Issue(index, agent, now);
  }
  return std::nullopt;
}

uint32_t DisplayPieces::HeldBy(scheduler::AgentId agent) const {
  const auto it = held_.find(agent);
  return it == held_.end() ? 0 : static_cast<uint32_t>(it->second.size());
}

void DisplayPieces::EndLease(uint32_t index, uint32_t attempt) {
  Slot& slot = slots_[index];
  slot.live.erase(attempt);
  if (slot.live.empty() && !slot.values && !slot.queued) {
    slot.queued = true;
    queue_.push_front(index);
  }
}

DisplayPieces::Verdict DisplayPieces::OnResult(scheduler::AgentId agent, uint64_t piece_id,
                                               uint32_t attempt, PointValues values) {
  const std::optional<uint32_t> index = IndexOf(piece_id);
  if (!index) return Verdict::kUnknown;
  auto held = held_.find(agent);
  const bool live =
      held != held_.end() && held->second.count(piece_id) && held->second.at(piece_id) == attempt;
  Slot& slot = slots_[*index];
  if (!live) return slot.values ? Verdict::kLate : Verdict::kUnknown;
  held->second.erase(piece_id);
  slot.live.erase(attempt);
  if (slot.values) return Verdict::kLate;
  slot.values = std::move(values);
  slot.queued = false;
  ++done_;
  return Verdict::kAccepted;
}

void DisplayPieces::OnAgentLost(scheduler::AgentId agent) {
  const auto it = held_.find(agent);
  if (it == held_.end()) return;
  const std::map<uint64_t, uint32_t> leases = std::move(it->second);
  held_.erase(it);
  for (const auto& [piece_id, attempt] : leases) EndLease(*IndexOf(piece_id), attempt);
}

void DisplayPieces::Return(scheduler::AgentId agent, uint64_t piece_id, uint32_t attempt) {
  const auto it = held_.find(agent);
  if (it == held_.end()) return;
  const auto lease = it->second.find(piece_id);
  if (lease == it->second.end() || lease->second != attempt) return;
  it->second.erase(lease);
  EndLease(*IndexOf(piece_id), attempt);
}

PointValues DisplayPieces::TakeValues() {
  if (!Complete()) {
    std::fprintf(stderr, "DisplayPieces::TakeValues: %zu of %zu pieces done\n", done_,
                 slots_.size());
    std::abort();
  }
  PointValues whole;
  for (Slot& slot : slots_) AppendPointValues(std::move(*slot.values), &whole);
  return whole;
}

}  // namespace radfarm::daemon
