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

namespace {

// The face's corners fanned into triangles; their UVs from the face's lightmap UV when it has one.
void Fan(const InputScene& scene, const InputFace& face, std::vector<LightmapTriangle>* out) {
  const bool mapped = face.lightmap_uv.size() == face.indices.size();
  for (size_t k = 1; k + 1 < face.indices.size(); ++k) {
    LightmapTriangle t;
    t.object = face.object;
    for (size_t c = 0; c < 3; ++c) {
      const size_t corner = c == 0 ? 0 : k + c - 1;
      t.position[c] = scene.positions[face.indices[corner]];
      if (mapped) t.uv[c] = face.lightmap_uv[corner];
    }
    out->push_back(t);
  }
}

}  // namespace

std::vector<LightmapTriangle> LightmapTriangles(const InputScene& scene) {
  std::vector<LightmapTriangle> out;
  for (const InputFace& face : scene.faces) {
    if (face.lightmap_uv.size() != face.indices.size()) continue;
    Fan(scene, face, &out);
  }
  return out;
}

std::vector<LightmapTriangle> UnmappedTriangles(const InputScene& scene) {
  std::vector<bool> mapped;
  for (const InputFace& face : scene.faces) {
    if (face.lightmap_uv.size() != face.indices.size()) continue;
    if (mapped.size() <= face.object) mapped.resize(face.object + 1, false);
    mapped[face.object] = true;
  }
  std::vector<LightmapTriangle> out;
  for (const InputFace& face : scene.faces) {
    if (face.object < mapped.size() && mapped[face.object]) continue;
    Fan(scene, face, &out);
  }
  return out;
}

}  // namespace radfarm
