// glTF nodes that carry an IES lamp in their extras, where Blender writes an object's custom
// properties: {"ies": "lamps/downlight.ies", "ies_multiplier": 1}. The lamp stands at the node's
// origin, aimed (vertical angle 0) along its -Z as glTF lamps are, with horizontal angle 0 toward
// its +X; the file is read as the scene's other files are (input/scene_directory.h) and parsed
// by input/ies_file.h.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <string>

#include "base/result.h"
#include "core/punctual_light.h"
#include "input/gltf_node_walk.h"
#include "input/scene_directory.h"

namespace radfarm {

// The IES lamp of `node`, or nullopt if its extras name none. `path` is the glTF file's, the file
// named is relative to its directory. Errors: "scene.gltf: node 3 'Downlight': extras.ies must
// be a string" (likewise an ies_multiplier not a number > 0, a degenerate transform, a file the
// scene may not read: "... extras.ies 'x.ies' leads outside ..."), and the IES file's own,
// after the node and located in the file ("scene.gltf: node 3 'Downlight': extras.ies:
// lamps/downlight.ies:9: ...").
Result<std::optional<PunctualLight>> ReadNodeIesLamp(const tinygltf::Model& model, int node,
                                                     const Mat4& world, const std::string& path,
                                                     const SceneDirectory& directory);

}  // namespace radfarm
