// Scene files by their extension: Wavefront OBJ (obj_scene_loader) or glTF 2.0 (.gltf, .glb).
#pragma once

#include <cstdint>
#include <string>

#include "base/result.h"
#include "base/text_file.h"
#include "input/input_scene.h"
#include "input/scene_directory.h"

namespace radfarm {

// Whether `path` names a scene file this reader knows (.obj, .gltf, .glb, any case).
bool IsSceneFile(const std::string& path);

// LoadObjScene or LoadGltfScene; any other extension is an error naming the file. The scene file
// must be a regular file of at most `max_file_bytes` (decided from its size, before reading).
// `max_texture_bytes` bounds a glTF's decoded images together (--max-memory; 0: each image at
// most kDefaultMaxTexturePixels pixels); OBJ scenes read no images. The files a scene names lie
// where `reach` allows (input/scene_directory.h). With `lamps_added` (the job places lamps or a
// sky of its own), a scene that emits nothing is no error.
Result<InputScene> LoadScene(const std::string& path,
                             uint64_t max_file_bytes = kDefaultMaxInputFileBytes,
                             uint64_t max_texture_bytes = 0,
                             FileReach reach = FileReach::kSceneTree, bool lamps_added = false);

}  // namespace radfarm
