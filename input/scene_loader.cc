#include "input/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "base/diagnostic.h"
#include "input/gltf_scene_loader.h"

namespace radfarm {
namespace {

std::string LowercaseExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool IsSceneFile(const std::string& path) {
  const std::string ext = LowercaseExtension(path);
  return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

Result<InputScene> LoadScene(const std::string& path) {
  const std::string ext = LowercaseExtension(path);
  if (ext == ".obj") return LoadObjScene(path);
  if (ext == ".gltf" || ext == ".glb") return LoadGltfScene(path);
  return ErrorAt(path, 0, "not a scene: expected a .obj, .gltf or .glb file");
}

}  // namespace radfarm
