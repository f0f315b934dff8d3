#include "output/layer_separation.h"

#include <algorithm>
#include <cmath>

namespace radfarm {

std::vector<Vec3> SeparatedLayerPositions(const DisplayMesh& mesh) {
  std::vector<Vec3> out = mesh.positions;
  if (mesh.patch_front_only.empty() || out.empty()) return out;
  Vec3 lo = out.front(), hi = out.front();
  for (const Vec3& p : out) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double gap = kLayerGap * Length(hi - lo);
  std::vector<Vec3> normal(out.size(), Vec3{0, 0, 0});
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const uint32_t patch = mesh.triangle_patch[t];
    if (patch >= mesh.patch_front_only.size() || !mesh.patch_front_only[patch]) continue;
    const auto& [a, b, c] = mesh.triangles[t];
    const Vec3 n = Cross(out[b] - out[a], out[c] - out[a]);  // twice the area, along the front
    for (uint32_t v : mesh.triangles[t]) normal[v] += n;
  }
  for (size_t v = 0; v < out.size(); ++v) {
    const double length = Length(normal[v]);
    if (length > 0 && std::isfinite(length)) out[v] += normal[v] * (gap / length);
  }
  return out;
}

}  // namespace radfarm
