#include "display/patch_mean_light.h"

#include <array>

#include "display/gouraud_means.h"

namespace radfarm {

PatchDirectSums MidpointRuleSums(const MidpointSplit& split, const std::vector<Rgb>& irradiance,
                                 size_t patches) {
  const DisplayMesh& fine = split.mesh;
  PatchDirectSums sums{std::vector<Rgb>(patches), std::vector<double>(patches, 0.0)};
  for (size_t t = 0; t < split.triangle_midpoints.size(); ++t) {
    const std::array<uint32_t, 3>& m = split.triangle_midpoints[t];
    const std::array<uint32_t, 3>& v = fine.triangles[4 * t + 3];  // a quarter of the triangle
    const Vec3& a = fine.positions[v[0]];
    const double twice_area = Length(Cross(fine.positions[v[1]] - a, fine.positions[v[2]] - a));
    const uint32_t f = fine.triangle_patch[4 * t];
    sums.sum[f] += (irradiance[m[0]] + irradiance[m[1]] + irradiance[m[2]]) * twice_area;
    sums.area[f] += twice_area;
  }
  return sums;
}

void RemeasureRefinedPatches(const DisplayMesh& fine, uint32_t first_new,
                             const std::vector<Rgb>& irradiance, PatchDirectSums* sums) {
  std::vector<bool> refined(sums->sum.size(), false);
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    for (uint32_t n : fine.triangles[t]) {
      if (n >= first_new) refined[fine.triangle_patch[t]] = true;
    }
  }
  for (size_t f = 0; f < refined.size(); ++f) {
    if (refined[f]) sums->sum[f] = Rgb(), sums->area[f] = 0;
  }
  for (size_t t = 0; t < fine.triangles.size(); ++t) {
    const uint32_t f = fine.triangle_patch[t];
    if (!refined[f]) continue;
    const std::array<uint32_t, 3>& v = fine.triangles[t];
    const Vec3& a = fine.positions[v[0]];
    const double twice_area = Length(Cross(fine.positions[v[1]] - a, fine.positions[v[2]] - a));
    sums->sum[f] += (irradiance[v[0]] + irradiance[v[1]] + irradiance[v[2]]) * twice_area;
    sums->area[f] += twice_area;
  }
}

void StepTowardMeanLight(const PatchScene& scene, const std::vector<Rgb>& rest,
                         const PatchDirectSums& sums, const std::vector<bool>& held,
                         DisplayMesh* fine) {
  const std::vector<Patch>& patches = scene.patches;
  std::vector<Rgb> target(patches.size());
  std::vector<bool> moves(patches.size());
  for (size_t f = 0; f < patches.size(); ++f) {
    moves[f] = patches[f].emission.Max() == 0 && sums.area[f] > 0;
    if (moves[f]) {
      target[f] = rest[f] + patches[f].reflectance * (sums.sum[f] / (3 * sums.area[f]));
    }
  }
  StepTowardPatchMeans(fine, target, moves, held);
}

}  // namespace radfarm
