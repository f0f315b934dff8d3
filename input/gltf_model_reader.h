// Reading a glTF file (.gltf with the buffer and image files it names, or .glb) into tinygltf's
// Model, every file read confined to the scene's directory (scene_directory.h) and bounded.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"

namespace radfarm {

// The scene file and the buffer and image files it names may hold at most `max_file_bytes`
// together: each is refused from its size before it is read once the files before it have used up
// the rest, and counted by the bytes actually read. A file the scene names must be a regular file
// inside the scene's directory tree (after symlinks, outside /proc, /sys and /dev), named by a
// relative uri; otherwise the load fails naming the scene, the field and the uri
// ("scene.gltf: buffers[2].uri '../secret' leads outside the scene's directory ..."), whether
// the file is a buffer or an image. tinygltf's warnings are appended to *warnings.
Result<tinygltf::Model> ReadGltfModel(const std::string& path, uint64_t max_file_bytes,
                                      std::vector<std::string>* warnings);

}  // namespace radfarm
