// Reading a glTF 2.0 scene (.gltf with its buffers and images, or .glb) into an InputScene, through
// tinygltf. Units and axes are glTF's (metres, +Y up) and are kept as they are, as OBJ
// coordinates are.
#pragma once

#include <string>

#include "base/result.h"
#include "base/text_file.h"
#include "input/input_scene.h"

namespace radfarm {

// The default scene (or the first), every node's mesh under its world transform (the node
// hierarchy, matrices or translation/rotation/scale; mirroring transforms flip the winding as glTF
// says), triangles indexed or not, materials as gltf_material.h describes, and the perspective
// cameras of the scene's nodes. Errors are one line naming the file and the node, mesh, primitive,
// material or accessor: unreadable file, primitive modes other than triangles, indices out of
// range, non-finite coordinates, bad factors, "nothing to light". Unsupported features that
// change little (alphaMode, skins, KHR_lights_punctual lamps) give warnings.
//
// The scene file and the buffer and image files it names are read as gltf_model_reader.h says:
// only regular files inside the scene's own directory tree, named by relative uris, together at
// most `max_file_bytes` ("path: the file is N bytes, over the limit of M bytes", M what is left).
// Images are bounded before they are decoded, by `max_texture_bytes` for all of them together or,
// when it is 0, by kDefaultMaxTexturePixels each (gltf_model_reader.h). `reach` widens where the
// files may lie (input/scene_directory.h). `lamps_added`: the job places lamps of its own, so
// "nothing to light" is no error.
Result<InputScene> LoadGltfScene(const std::string& path,
                                 uint64_t max_file_bytes = kDefaultMaxInputFileBytes,
                                 uint64_t max_texture_bytes = 0,
                                 FileReach reach = FileReach::kSceneTree, bool lamps_added = false);

}  // namespace radfarm
