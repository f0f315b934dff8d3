// The display's cuts where the light bends: a penumbra, a lamp's fall-off, a corner's gathered
// light. Up to kDisplayRefineLevels levels, each cutting the triangles whose corners differ too
// much; the new points' light is traced as the first points' (display/point_work.h) and then set.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/point_gather.h"
#include "core/rgb.h"
#include "display/display_mesh.h"
#include "display/selective_split.h"

namespace radfarm {

// What the display knows of each of its points besides the radiance it shows.
struct PointLight {
  std::vector<bool> held;         // gathered: its value is its own, not a stand-in for a mean
  std::vector<Rgb> irradiance;    // the direct light at the point
  std::vector<Rgb> shown_direct;  // rho times that
};

// What a level's points will cost under an allowance (display/display_ray_plan.h): each point's
// shadow rays and each gathering point's rays as the display's first points spent them on average.
struct LevelRays {
  std::optional<uint64_t> allowance;
  double direct_per_point = 0;
  double gather_per_point = 0;
  uint32_t gather_rays = kPointGatherRays;
};

// A level's cut: the split mesh and, per new point, where its light is computed (a hair toward
// the centroids of the triangles around it, facing as their patches do), their reflectance and
// whether it gathers (it lies between two points that hold gathered light).
struct LevelCut {
  SelectiveSplit split;
  std::vector<ReceiverPoint> points;
  std::vector<Rgb> rho;
  std::vector<bool> gathers;
};

// The next level's cut of `fine`, or none where the light bends nowhere or the level's points
// would take `rays` past the allowance. A triangle whose corners all hold their own light (held:
// gathered) is cut where their light differs by more than CutContrast (display/display_cut.h) of
// the brightest; any other where the direct light shown at its corners does, a shadow's edge or a
// lamp's fall-off. Emitters are never cut.
std::optional<LevelCut> CutWhereLightBends(const PatchScene& scene, const DisplayMesh& fine,
                                           const PointLight& light, const LevelRays& budget,
                                           uint64_t rays);

// Sets the cut's new points to their light, `gathered` and `irradiance` per new point: a gathering
// point shows rho times the direct and the gathered light and is held; any other the direct light
// at itself plus the rest interpolated between its edge's ends. `*fine` becomes the cut mesh.
void ApplyLevelCut(LevelCut cut, const std::vector<Rgb>& gathered,
                   const std::vector<Rgb>& irradiance, DisplayMesh* fine, PointLight* light);

}  // namespace radfarm
