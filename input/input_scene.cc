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

std::vector<LightmapTriangle> LightmapTriangles(const InputScene& scene) {
  std::vector<LightmapTriangle> out;
  for (const InputFace& face : scene.faces) {
    if (face.lightmap_uv.size() != face.indices.size()) continue;
    for (size_t k = 1; k + 1 < face.indices.size(); ++k) {
      LightmapTriangle t;
      t.object = face.object;
      for (size_t c = 0; c < 3; ++c) {
        const size_t corner = c == 0 ? 0 : k + c - 1;
        t.position[c] = scene.positions[face.indices[corner]];
        t.uv[c] = face.lightmap_uv[corner];
      }
      out.push_back(t);
    }
  }
  return out;
}

}  // namespace radfarm
