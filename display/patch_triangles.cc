#include "display/patch_triangles.h"

#include "mesh/ear_clip.h"
#include "mesh/polygon.h"

namespace radfarm {

DisplayMesh PatchTriangles(const DisplayTopology& topology, const PatchScene& scene,
                           std::vector<Rgb> radiance) {
  const std::vector<Patch>& patches = scene.patches;
  DisplayMesh out;
  out.positions = topology.positions;
  out.radiance = std::move(radiance);
  for (const Patch& patch : patches) {
    if (!patch.two_sided) continue;
    out.patch_front_only.resize(patches.size());
    break;
  }
  if (!out.patch_front_only.empty()) {
    for (uint32_t f = 0; f < patches.size(); ++f) out.patch_front_only[f] = patches[f].two_sided;
  }
  std::vector<Vec3> ring_positions;
  for (uint32_t f = 0; f < patches.size(); ++f) {
    const std::vector<uint32_t>& ring = topology.rings[f];
    const int n = patches[f].corner_count;
    if (static_cast<int>(ring.size()) == n) {
      for (int j = 1; j + 1 < n; ++j) {
        out.triangles.push_back({ring[0], ring[j], ring[j + 1]});
        out.triangle_patch.push_back(f);
      }
      continue;
    }
    ring_positions.clear();
    for (uint32_t v : ring) ring_positions.push_back(out.positions[v]);
    const EarClipResult clip =
        EarClip(ProjectToPlane(ring_positions, ring_positions[0], patches[f].normal));
    for (const auto& t : clip.triangles) {
      out.triangles.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
      out.triangle_patch.push_back(f);
    }
  }
  return out;
}

}  // namespace radfarm
