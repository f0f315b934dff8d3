#include "input/scene_loader.h"

#include <filesystem>

#include "base/diagnostic.h"
#include "base/file_extension.h"
#include "input/gltf_scene_loader.h"

namespace radfarm {

bool IsSceneFile(const std::string& path) {
  const std::string ext = LowercaseExtension(path);
  return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

Result<InputScene> LoadScene(const std::string& path, uint64_t max_file_bytes,
                             uint64_t max_texture_bytes, FileReach reach, bool lamps_added) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  // A device, FIFO or directory: ReadTextFile names what it is without reading a byte.
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return Error{ReadTextFile(path, max_file_bytes).error()};
  }
  const std::string ext = LowercaseExtension(path);
  if (ext == ".obj") return LoadObjScene(path, max_file_bytes, reach, lamps_added);
  // tinygltf reads through LoadGltfScene's bounded reads, which refuse an oversized file (and
  // oversized buffers and images it references) from their size first.
  if (ext == ".gltf" || ext == ".glb")
    return LoadGltfScene(path, max_file_bytes, max_texture_bytes, reach, lamps_added);
  return ErrorAt(path, 0, "not a scene: expected a .obj, .gltf or .glb file");
}

}  // namespace radfarm
