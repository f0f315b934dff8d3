#include "core/gathering_patches.h"

namespace radfarm {

bool FacesTheVoid(const Patch& patch, const Bounds3& bounds) {
  if (bounds.Empty()) return false;
  const double tolerance = 1e-7 * bounds.Diagonal();
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner = {(k & 1) ? bounds.hi.x : bounds.lo.x, (k & 2) ? bounds.hi.y : bounds.lo.y,
                         (k & 4) ? bounds.hi.z : bounds.lo.z};
    if (Dot(corner - patch.centre, patch.normal) > tolerance) return false;
  }
  return true;
}

std::vector<bool> GatheringPatchMask(const PatchScene& scene) {
  Bounds3 bounds;
  for (const Patch& p : scene.patches) {
    for (int c = 0; c < p.corner_count; ++c) bounds.Extend(p.corners[c]);
  }
  std::vector<bool> mask(scene.patches.size());
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    mask[i] = p.reflectance.Max() > 0 && !FacesTheVoid(p, bounds);
  }
  return mask;
}

}  // namespace radfarm
