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

// The same checks, but each patch goes to `each` (with its index and the patch count) as it is
// decoded instead of into a scene, so a caller that keeps only part of each patch (an agent,
// agent/prepared_scene.h) never holds them all; `rest`, when given, gets the material names and
// lights. Returns the patch count. On an error some patches may have gone to `each`.
Result<uint32_t> DecodePatches(
    std::span<const uint8_t> blob,
    const std::function<void(const Patch& patch, uint32_t index, uint32_t count)>& each,
    PatchScene* rest = nullptr);

// DecodePatches for bytes it has accepted before (an agent's own copy of a blob it checked, in a
// file replaced only whole): the same patches and value checks, without FlatBuffers' verification
// of the whole buffer first, which reads every page of it at once (a mapped file's pages would all
// be resident together); each patch's bytes are read only when it is decoded.
Result<uint32_t> DecodeAcceptedPatches(
    std::span<const uint8_t> blob,
    const std::function<void(const Patch& patch, uint32_t index, uint32_t count)>& each);

}  // namespace radfarm::codec
