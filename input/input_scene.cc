#include "input/input_scene.h"

#include <filesystem>

namespace radfarm {

std::string DefaultObjectName(const std::string& scene_path) {
  const std::string stem = std::filesystem::path(scene_path).stem().string();
  return stem.empty() ? "scene" : stem;
}

std::vector<InputObject> ObjectsOrDefault(const InputScene& scene) {
  if (!scene.objects.empty()) return scene.objects;
  InputObject object;
  object.name = DefaultObjectName(scene.path);
  object.has_faces = !scene.faces.empty();
  return {object};
}

}  // namespace radfarm
