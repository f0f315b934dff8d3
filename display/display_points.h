// Where the display computes light: a point a hair inside the patches around each display vertex
// and each midpoint of the display triangles (display/midpoint_split.h), facing as those patches
// do, with their mean reflectance. A vertex on a crease or at the foot of a wall so sees the light
// as the surface beside it does.
#pragma once

#include <cstdint>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/rgb.h"
#include "display/midpoint_split.h"
#include "mesh/display_topology.h"

namespace radfarm {

inline constexpr uint32_t kNoDisplayPoint = ~uint32_t{0};

struct DisplayPoints {
  std::vector<ReceiverPoint> points;
  // Per point: whether it may gather its own light (not beside an emitter, which shows its
  // emission and keeps the average).
  std::vector<bool> may_gather;
  // Per vertex of the split mesh (the display vertices, then the midpoints): its point, or
  // kNoDisplayPoint where its patches give it no normal.
  std::vector<uint32_t> point_of;
  // Per vertex of the split mesh: the area-weighted mean reflectance of its patches.
  std::vector<Rgb> rho;
};

// The points of the display vertices of `topology`, then of the midpoints of `split` (the patch
// triangles cut at their midpoints).
DisplayPoints PlaceDisplayPoints(const DisplayTopology& topology, const PatchScene& scene,
                                 const MidpointSplit& split);

}  // namespace radfarm
