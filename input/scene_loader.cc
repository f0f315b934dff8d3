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

Result<InputScene> LoadScene(const std::string& path, uint64_t max_file_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  // A device, FIFO or directory: ReadTextFile names what it is without reading a byte.
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return Error{ReadTextFile(path, max_file_bytes).error()};
  }
  const std::string ext = LowercaseExtension(path);
  if (ext == ".obj") return LoadObjScene(path, max_file_bytes);
  if (ext == ".gltf" || ext == ".glb") {
    // tinygltf reads the file itself: refuse an oversized one from its size first.
    if (std::filesystem::is_regular_file(status)) {
      const uint64_t size = std::filesystem::file_size(path, ec);
      if (!ec && size > max_file_bytes) {
        return Error{path + ": the file is " + std::to_string(size) + " bytes, over the limit of " +
                     std::to_string(max_file_bytes) + " bytes"};
      }
    }
    return LoadGltfScene(path);
  }
  return ErrorAt(path, 0, "not a scene: expected a .obj, .gltf or .glb file");
}

}  // namespace radfarm
