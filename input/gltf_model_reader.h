// Reading a glTF file (.gltf with the buffer and image files it names, or .glb) into tinygltf's
// Model, every file read confined to the scene's directory (scene_directory.h) and bounded.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "input/scene_directory.h"

namespace radfarm {

// The scene file and the buffer and image files it names may hold at most `max_file_bytes`
// together: each is refused from its size before it is read once the files before it have used up
// the rest, and counted by the bytes actually read. A file the scene names must be a regular file
// inside the scene's directory tree (after symlinks, outside /proc, /sys and /dev), named by a
// relative uri; otherwise the load fails naming the scene, the field and the uri
// ("scene.gltf: buffers[2].uri '../secret' leads outside the scene's directory ..."), whether
// the file is a buffer or an image. tinygltf's warnings are appended to *warnings.
//
// Images (PNG, JPEG, or BMP) are bounded from their headers before they are decoded: with
// `max_texture_bytes` 0, each may have at most kDefaultMaxTexturePixels pixels; otherwise all
// images together may decode to at most `max_texture_bytes` (--max-memory). The error names the
// scene, the image, its size and the limit. Images decode to RGBA, 8- or 16-bit (a 16-bit PNG);
// decoding needs about twice an image's decoded bytes for a moment (stb_image's buffer, then
// tinygltf's copy of it), and the model keeps the copy.
Result<tinygltf::Model> ReadGltfModel(const std::string& path, uint64_t max_file_bytes,
                                      uint64_t max_texture_bytes,
                                      std::vector<std::string>* warnings,
                                      FileReach reach = FileReach::kSceneTree);

// The most pixels a texture may have when no memory limit is given: 512 MB of 16-bit RGBA.
inline constexpr uint64_t kDefaultMaxTexturePixels = uint64_t{8192} * 8192;

}  // namespace radfarm
