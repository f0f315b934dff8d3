// A display step's PointContext with its scene as bytes (schema/point_context.fbs): the master
// encodes one per step of a job's display, and agents fetch it by its hash and decode it into a
// PointTracer's inputs (display/point_context.h). Every value is copied exactly, so the lights
// built from it are the master's bits.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "core/patch_scene.h"
#include "display/point_context.h"
#include "mesh/patch_mesh.h"

namespace radfarm::codec {

// `scene` is the scene's blob (EncodePatchScene), carried as it is.
std::vector<uint8_t> EncodePointContext(std::span<const uint8_t> scene,
                                        const PointContext& context);

struct DecodedPointContext {
  PatchScene scene;
  PointContext context;
};

// The elements a point context's score work may hold: as many as a mesh's patches may be.
inline constexpr size_t kMaxScoreElements = kMaxPatches;

// Checks the scene as DecodePatchScene does, and the context: rays per point at least 1 and
// within bounds, the gathering arrays all absent or one per patch (four offsets per patch),
// finite values, a finite positive reach, score work absent or with 1..kLightSources sources, a
// finite positive tolerance and 1..kMaxScoreElements elements of 3 or 4 corners. Errors name the
// field.
Result<DecodedPointContext> DecodePointContext(std::span<const uint8_t> blob);

}  // namespace radfarm::codec
