#include "loop/frame_budget.h"

#include <algorithm>

#include "loop/check.h"

namespace radfarm::loop {

uint64_t FrameBudget::Join(OnEvicted on_evicted) {
  const uint64_t holder = next_holder_++;
  holders_.emplace(holder, Holder{0, std::move(on_evicted)});
  return holder;
}

void FrameBudget::Leave(uint64_t holder) {
  const auto it = holders_.find(holder);
  if (it == holders_.end()) return;
  held_ -= it->second.held;
  holders_.erase(it);
}

uint64_t FrameBudget::held_by(uint64_t holder) const {
  const auto it = holders_.find(holder);
  return it == holders_.end() ? 0 : it->second.held;
}

std::map<uint64_t, FrameBudget::Holder>::iterator FrameBudget::Largest(uint64_t asking) {
  auto largest = holders_.end();
  for (auto it = holders_.begin(); it != holders_.end(); ++it) {
    if (it->first == asking) continue;
    if (largest == holders_.end() || it->second.held > largest->second.held) largest = it;
  }
  return largest;
}

void FrameBudget::Evict(std::map<uint64_t, Holder>::iterator victim, uint64_t wanted) {
  const std::string reason = "closed holding the most bytes of unfinished frames (" +
                             std::to_string(victim->second.held) +
                             ") when another connection's frame needed " + std::to_string(wanted) +
                             " more: unfinished frames already hold " + std::to_string(held_) +
                             " of the " + std::to_string(limit_) + " bytes allowed (" + name_ + ")";
  held_ -= victim->second.held;
  ++refused_;
  ++evicted_;
  // Out of the table first: the callback closes a connection whose splitter then leaves.
  const OnEvicted on_evicted = std::move(victim->second.on_evicted);
  holders_.erase(victim);
  if (on_evicted) on_evicted(reason);
}

bool FrameBudget::Take(uint64_t holder, uint64_t bytes) {
  const auto self = holders_.find(holder);
  LOOP_CHECK(self != holders_.end());
  if (bytes > limit_ - held_) {
    // Only holders that would still hold more than this one may go for it; if even all of them
    // going leaves no room, this one is the largest problem and is refused alone.
    const uint64_t would_hold = self->second.held + bytes;
    uint64_t larger = 0;
    for (const auto& [id, h] : holders_)
      if (id != holder && h.held > would_hold) larger += h.held;
    if (bytes > limit_ - (held_ - larger)) {
      ++refused_;
      return false;
    }
    while (bytes > limit_ - held_) Evict(Largest(holder), bytes);
  }
  self->second.held += bytes;
  held_ += bytes;
  peak_ = std::max(peak_, held_);
  return true;
}

void FrameBudget::Give(uint64_t holder, uint64_t bytes) {
  const auto it = holders_.find(holder);
  if (it == holders_.end()) return;  // evicted: its share went back then
  LOOP_CHECK(bytes <= it->second.held);
  it->second.held -= bytes;
  held_ -= bytes;
}

}  // namespace radfarm::loop
