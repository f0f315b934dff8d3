#include "input/fuzz/loaded_scene_check.h"

#include <cmath>
#include <cstdlib>

namespace radfarm::fuzz {

void CheckLoadedScene(const InputScene& scene) {
  for (const Vec3& p : scene.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
  }
  const size_t objects = scene.objects.empty() ? 1 : scene.objects.size();
  for (const InputFace& face : scene.faces) {
    if (face.indices.size() < 3) std::abort();
    for (uint32_t index : face.indices) {
      if (index >= scene.positions.size()) std::abort();
    }
    if (face.material >= scene.materials.size() || face.object >= objects) std::abort();
  }
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (scene.objects[i].parent >= static_cast<int32_t>(i)) std::abort();
  }
}

}  // namespace radfarm::fuzz
