#include "mesh/midpoint_split.h"

#include <algorithm>
#include <unordered_map>

namespace radfarm {

MidpointSplit SplitAtMidpoints(const DisplayMesh& coarse) {
  MidpointSplit out;
  out.coarse_vertices = static_cast<uint32_t>(coarse.positions.size());
  DisplayMesh& fine = out.mesh;
  fine.positions = coarse.positions;
  fine.radiance = coarse.radiance;
  fine.radiance.resize(coarse.positions.size());
  fine.patch_front_only = coarse.patch_front_only;
  fine.triangles.reserve(4 * coarse.triangles.size());
  fine.triangle_patch.reserve(4 * coarse.triangles.size());
  out.triangle_midpoints.reserve(coarse.triangles.size());
  std::unordered_map<uint64_t, uint32_t> midpoint_of_edge;
  midpoint_of_edge.reserve(2 * coarse.triangles.size());
  for (size_t t = 0; t < coarse.triangles.size(); ++t) {
    const std::array<uint32_t, 3>& v = coarse.triangles[t];
    std::array<uint32_t, 3> m{};
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      const uint64_t key = uint64_t{std::min(a, b)} << 32 | std::max(a, b);
      const auto [it, added] =
          midpoint_of_edge.try_emplace(key, static_cast<uint32_t>(fine.positions.size()));
      if (added) {
        fine.positions.push_back((coarse.positions[a] + coarse.positions[b]) * 0.5);
        fine.radiance.push_back((fine.radiance[a] + fine.radiance[b]) * 0.5);
        out.edge_ends.push_back({a, b});
      }
      m[k] = it->second;
    }
    out.triangle_midpoints.push_back(m);
    const uint32_t patch = coarse.triangle_patch[t];
    fine.triangles.push_back({v[0], m[0], m[2]});
    fine.triangles.push_back({m[0], v[1], m[1]});
    fine.triangles.push_back({m[2], m[1], v[2]});
    fine.triangles.push_back({m[0], m[1], m[2]});
    for (int k = 0; k < 4; ++k) fine.triangle_patch.push_back(patch);
  }
  return out;
}

}  // namespace radfarm
