#include "mesh/locate_patches.h"

#include "core/ray_caster.h"

namespace radfarm {

std::vector<uint32_t> LocatePoints(const PatchScene& mesh,
                                   const std::vector<SurfacePoint>& points) {
  const RayCaster caster(mesh);
  // Start ten ray offsets in front of the surface: clear of it, yet far closer than anything else.
  const double lift = 10 * caster.origin_offset();
  std::vector<uint32_t> out;
  out.reserve(points.size());
  for (const SurfacePoint& p : points) {
    const RayHit hit = caster.Trace(p.position + p.normal * lift, p.normal * -1.0, p.normal);
    out.push_back(hit.patch != RayHit::kMiss && hit.front ? hit.patch : kNoPatch);
  }
  return out;
}

std::vector<uint32_t> LocatePatchCentres(const PatchScene& mesh, const PatchScene& points) {
  std::vector<SurfacePoint> centres;
  centres.reserve(points.patches.size());
  for (const Patch& p : points.patches) centres.push_back({p.centre, p.normal});
  return LocatePoints(mesh, centres);
}

}  // namespace radfarm
