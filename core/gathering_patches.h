// Which patches the final gather gathers for (core/progressive_solver.h). A patch that reflects
// nothing shows only its emission. A patch facing the void shows only its emission and its direct
// light: every corner of the scene's bounds lies on or behind its plane, so nothing stands in
// front of it and every gather ray would leave the scene. That is the outer layer of a two-sided
// wall of a closed room (a Blender room with outward normals): its gather would be wasted work,
// and its escaped rays would read as a leak. Skipping it leaves its radiosity as the gather would
// have made it, to the bit (emission + reflectance * (direct + nothing)).
#pragma once

#include <vector>

#include "core/patch_scene.h"

namespace radfarm {

// Whether every corner of `bounds` lies on or behind the plane of `patch` (within a tolerance of
// 1e-7 of the bounds' diagonal).
bool FacesTheVoid(const Patch& patch, const Bounds3& bounds);

// By patch: gathers when it reflects and does not face the void of the scene's bounds.
std::vector<bool> GatheringPatchMask(const PatchScene& scene);

}  // namespace radfarm
