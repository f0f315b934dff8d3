#include "mesh/locate_patches.h"

#include "core/ray_caster.h"

namespace radfarm {

std::vector<uint32_t> LocatePatchCentres(const PatchScene& mesh, const PatchScene& points) {
  const RayCaster caster(mesh);
  // Start ten ray offsets in front of the surface: clear of it, yet far closer than anything else.
  const double lift = 10 * caster.origin_offset();
  std::vector<uint32_t> out;
  out.reserve(points.patches.size());
  for (const Patch& p : points.patches) {
    const RayHit hit = caster.Trace(p.centre + p.normal * lift, p.normal * -1.0, p.normal);
    out.push_back(hit.patch != RayHit::kMiss && hit.front ? hit.patch : kNoPatch);
  }
  return out;
}

}  // namespace radfarm
