// RecentScenes: the prepared scenes the agent keeps in memory, most recently used first. Building a
// RayCaster is the expensive step, so the last `capacity` scenes stay ready; older ones are let go
// (batches still running on one keep it alive through their shared_ptr). Loop thread only.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>

#include "agent/prepared_scene.h"

namespace radfarm::agent {

class RecentScenes {
 public:
  explicit RecentScenes(size_t capacity = 2) : capacity_(capacity) {}

  // The scene, now the most recently used; null if not kept.
  std::shared_ptr<const PreparedScene> Find(const protocol::SceneHash& hash);
  // Keeps `scene` as the most recently used, letting the least recently used go beyond capacity.
  void Insert(std::shared_ptr<const PreparedScene> scene);
  size_t size() const { return scenes_.size(); }

 private:
  size_t capacity_;
  std::deque<std::shared_ptr<const PreparedScene>> scenes_;  // most recent first
};

}  // namespace radfarm::agent
