// The scene blob agents receive: a PatchScene (patch corners, normals, areas, materials) encoded as
// a FlatBuffer (schema/patch_scene.fbs). The master names it by its SHA-256 (protocol/
// scene_transfer.h); an agent decodes it and builds its RayCaster from it. Encoding is exact
// (doubles as bits) and deterministic (same scene, same bytes, same hash).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"

namespace radfarm::codec {

std::vector<uint8_t> EncodePatchScene(const PatchScene& scene);
// The same bytes, lent to `use` while the encoder holds them: no copy (the master packs the scene
// straight from here, protocol/scene_packing.h).
void EncodePatchScene(const PatchScene& scene,
                      const std::function<void(std::span<const uint8_t> blob)>& use);

// Verifies the buffer and every value (finite numbers, 3..4 corners, positive areas, reflectance
// in [0, 1), emission >= 0, material ids in range) before building the scene. Errors name the
// field and the patch.
Result<PatchScene> DecodePatchScene(std::span<const uint8_t> blob);

}  // namespace radfarm::codec
