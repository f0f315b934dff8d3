// Scene files by their extension: Wavefront OBJ (obj_scene_loader) or glTF 2.0 (.gltf, .glb).
#pragma once

#include <string>

#include "base/result.h"
#include "input/input_scene.h"

namespace radfarm {

// Whether `path` names a scene file this reader knows (.obj, .gltf, .glb, any case).
bool IsSceneFile(const std::string& path);

// LoadObjScene or LoadGltfScene; any other extension is an error naming the file.
Result<InputScene> LoadScene(const std::string& path);

}  // namespace radfarm
