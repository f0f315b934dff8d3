// glTF KHR_lights_punctual: the lamp a node carries, placed by the node's world transform.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <string>

#include "base/result.h"
#include "core/punctual_light.h"
#include "input/gltf_node_walk.h"

namespace radfarm {

// The light of `node` (its extensions' KHR_lights_punctual.light), or nullopt if it has none.
// Positions come from the world matrix, directions from its -Z (normalised: the node's scale
// changes neither intensity nor range, as the extension says). A missing colour is white, a
// missing intensity 1, a missing range unlimited; spot cones default to 0 and pi/4. Errors name
// the node and the light: an index out of range, an unknown type, values the extension forbids
// (negative intensity or range, cones outside 0 <= inner < outer <= pi/2).
Result<std::optional<PunctualLight>> ReadNodeLight(const tinygltf::Model& model, int node,
                                                   const Mat4& world);

}  // namespace radfarm
