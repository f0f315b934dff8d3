// Where the emitters' light lands, front or back, per material: a cheap look before the solve that
// finds surfaces modelled facing the wrong way (a room built as a cube with outward normals: every
// wall is hit from behind, absorbs the light and renders black).
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/ray_caster.h"

namespace radfarm {

struct BackFaceCounts {
  // By material index (PatchScene::material_names): rays whose first hit was the material's
  // front, and its back.
  std::vector<uint64_t> front;
  std::vector<uint64_t> back;
  uint64_t rays = 0;  // all rays cast, escaped ones included
};

// Casts about `rays` rays from the emitting patches and the point and spot lamps
// (PatchScene::lights; suns are left out), each one's share in proportion to its emitted power,
// and counts first hits per material and side. Deterministic (fixed Sobol rays from patches,
// counter-based ones from lamps).
BackFaceCounts SurveyBackFaces(const PatchScene& scene, const RayCaster& caster, uint64_t rays);

}  // namespace radfarm
