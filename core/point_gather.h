// The bounced light arriving at single points, gathered by rays from the solved patches: what a
// display point near another surface shows instead of an average of its patches.
//
// A patch's solution is a mean over its area. Where another surface is near (a corner, the foot of
// a wall, the ceiling around a hanging lamp, the floor beside a block), the light a point receives
// changes within a patch: the surface beside it hides part of the room. An average of the patches
// around a vertex, or an extrapolation from inside, then draws corners too dark or too bright and
// smears a lamp's shadow on the ceiling across its outline. So a point with another surface within
// about a patch size and a half (NearOtherSurfaces) gathers: its irradiance is the mean, over
// cosine-weighted rays, of the outgoing light of the patch each meets (nothing for a miss or the
// back of a one-sided patch). Points in open space keep their average, smooth there and noiseless.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/direct_light.h"
#include "core/patch_scene.h"
#include "core/ray_caster.h"
#include "core/rgb.h"

namespace radfarm {

// Rays per gathering point: the standard error of the irradiance in a room's corner is then about
// 0.25 %; a small bright source alone is a binomial draw, sqrt(F (1 - F) / 512) of form factor F
// (a randomised Sobol sequence per point; tests/core/point_gather_test.cc).
inline constexpr uint32_t kPointGatherRays = 512;

// Whether a patch of another plane than the point's own lies within `radius` of it, not wholly
// behind it (an Embree point query on the caster's BVH). A pure function of its arguments.
std::vector<bool> NearOtherSurfaces(const PatchScene& scene, const RayCaster& caster,
                                    const std::vector<ReceiverPoint>& points, double radius,
                                    unsigned threads);

// How the light leaving each patch varies across it: at each of its corners (Patch::corners'
// order), the light leaving there less the patch's mean. A patch's mean is what the solution
// holds, but a gathering point near it sees mostly the part of it nearest: the top of a wall
// below a ceiling, where the lamps hanging under the ceiling send no direct light, is darker
// than the wall's top patch on average, and a ceiling point beside it gathering the mean was drawn
// too bright. With these offsets a ray that meets the patch counts its mean plus the offsets
// interpolated at the hit (linearly over the triangles (0, 1, 2) and (0, 2, 3)).
struct PatchCornerOffsets {
  const PatchScene* scene = nullptr;        // the patches the caster was built from
  std::vector<std::array<Rgb, 4>> offsets;  // per patch
};

// The offsets interpolated at `x`, a point in the plane of patch p.
Rgb InterpolateCornerOffsets(const Patch& p, const std::array<Rgb, 4>& offsets, const Vec3& x);

// The bounced light a patch reflects is a mean over its area too, and a ray that meets a patch
// within about the patch's size of where it started sees only the part nearest: in a crevice
// behind a cabinet the wall's patch is brighter toward the opening than behind the point, and
// the top of a wall right under a ceiling meets a ceiling that is darker beside the wall than its
// patch's mean. Such a ray gathers once more where it meets: one cosine-weighted ray from the hit
// takes the place of the patch's mean bounced light. Near: closer than kSecondBounceReach times
// sqrt(area) of the patch met. Scored against the path-traced reference on the building
// (docs/BENCHMARKS-accuracy.md), a reach of 2 did best: any reach beats none, and a longer one
// gathers again where the patch's mean was good enough, and each second ray adds noise.
inline constexpr double kSecondBounceReach = 2;

struct SecondBounce {
  const PatchScene* scene = nullptr;  // the patches the caster was built from (reflectance, area)
  // Per patch: the part of `outgoing` that is its reflected bounced light (outgoing less rho
  // times its mean direct light, less its emission where `outgoing` holds it).
  std::vector<Rgb> bounced;
  // A hit closer than this many times sqrt(area) of the patch it meets gathers again.
  double reach = kSecondBounceReach;
};

// For each point with gather[i] set, the mean over `rays` cosine-weighted rays of `outgoing` (one
// value per patch: the light leaving it that the point should count, plus `corners`' offsets at
// the hit when given, its bounced part gathered again at a near hit when `second` is given) at
// the patch each meets; zero elsewhere; `outgoing` follows the patches of the scene `caster` was
// built from. A pure function of its arguments, whatever the thread count; `seed` keys the rays
// of point i with first_index + i, so the points of a longer list traced in pieces, each with
// its first point's index there, get the whole list's values. `rays_cast`, if not null, is
// increased by the rays cast, second bounces included (the same whatever the thread count).
std::vector<Rgb> GatherLight(const RayCaster& caster, const std::vector<Rgb>& outgoing,
                             const std::vector<ReceiverPoint>& points,
                             const std::vector<bool>& gather, uint64_t seed, unsigned threads,
                             uint32_t rays = kPointGatherRays,
                             const PatchCornerOffsets* corners = nullptr,
                             const SecondBounce* second = nullptr, uint64_t* rays_cast = nullptr,
                             uint64_t first_index = 0);

}  // namespace radfarm
