// Which patch of one meshing of a scene holds each point of another meshing of the same scene:
// used to compare solutions on different meshes (a refined mesh against its coarse start, any mesh
// against a fine reference). A ray from just in front of the point straight back at its surface
// finds the patch under it; points that find nothing facing them get kNoPatch.
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"

namespace radfarm {

inline constexpr uint32_t kNoPatch = 0xffffffffu;

struct SurfacePoint {
  Vec3 position;
  Vec3 normal;  // unit, the side the point faces
};

// For each point, the patch of `mesh` under it.
std::vector<uint32_t> LocatePoints(const PatchScene& mesh, const std::vector<SurfacePoint>& points);

// For each patch of `points`, the patch of `mesh` under its centre.
std::vector<uint32_t> LocatePatchCentres(const PatchScene& mesh, const PatchScene& points);

}  // namespace radfarm
