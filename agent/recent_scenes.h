// RecentPrepared: the prepared scenes (or point contexts) the agent keeps in memory, most recently
// used first. Building a RayCaster is the expensive step, so the last `capacity` stay ready; older
// ones are let go (work still running on one keeps it alive through its shared_ptr). Loop thread
// only.
#pragma once

#include <algorithm>
#include <cstddef>
#include <deque>
#include <memory>

#include "agent/prepared_context.h"
#include "agent/prepared_scene.h"
#include "protocol/messages.h"

namespace radfarm::agent {

// `T` has a `hash` (a protocol::SceneHash).
template <typename T>
class RecentPrepared {
 public:
  explicit RecentPrepared(size_t capacity = 2) : capacity_(capacity) {}

  // The item, now the most recently used; null if not kept.
  std::shared_ptr<const T> Find(const protocol::SceneHash& hash) {
    auto found = std::find_if(items_.begin(), items_.end(),
                              [&hash](const auto& item) { return item->hash == hash; });
    if (found == items_.end()) return nullptr;
    std::shared_ptr<const T> item = *found;
    items_.erase(found);
    items_.push_front(item);
    return item;
  }
  // Keeps `item` as the most recently used, letting the least recently used go beyond capacity.
  void Insert(std::shared_ptr<const T> item) {
    if (Find(item->hash)) return;
    items_.push_front(std::move(item));
    while (items_.size() > capacity_) items_.pop_back();
  }
  size_t size() const { return items_.size(); }

 private:
  size_t capacity_;
  std::deque<std::shared_ptr<const T>> items_;  // most recent first
};

using RecentScenes = RecentPrepared<PreparedScene>;
// A display has at most two contexts: its direct-light step's and the rest's.
using RecentContexts = RecentPrepared<PreparedContext>;

}  // namespace radfarm::agent
