#include "agent/recent_scenes.h"

#include <algorithm>

namespace radfarm::agent {

std::shared_ptr<const PreparedScene> RecentScenes::Find(const protocol::SceneHash& hash) {
  auto found = std::find_if(scenes_.begin(), scenes_.end(),
                            [&hash](const auto& scene) { return scene->hash == hash; });
  if (found == scenes_.end()) return nullptr;
  std::shared_ptr<const PreparedScene> scene = *found;
  scenes_.erase(found);
  scenes_.push_front(scene);
  return scene;
}

void RecentScenes::Insert(std::shared_ptr<const PreparedScene> scene) {
  if (Find(scene->hash)) return;
  scenes_.push_front(std::move(scene));
  while (scenes_.size() > capacity_) scenes_.pop_back();
}

}  // namespace radfarm::agent
