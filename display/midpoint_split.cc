#include "display/midpoint_split.h"

#include "mesh/triangle_edges.h"

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
  const TriangleEdges edges = IndexEdges(coarse.triangles, coarse.positions.size());
  constexpr uint32_t kNone = ~uint32_t{0};
  std::vector<uint32_t> midpoint_of_edge(edges.edges(), kNone);
  for (size_t t = 0; t < coarse.triangles.size(); ++t) {
    const std::array<uint32_t, 3>& v = coarse.triangles[t];
    std::array<uint32_t, 3> m{};
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      uint32_t& midpoint = midpoint_of_edge[edges.edge_of[3 * t + k]];
      if (midpoint == kNone) {
        midpoint = static_cast<uint32_t>(fine.positions.size());
        fine.positions.push_back((coarse.positions[a] + coarse.positions[b]) * 0.5);
        fine.radiance.push_back((fine.radiance[a] + fine.radiance[b]) * 0.5);
        out.edge_ends.push_back({a, b});
      }
      m[k] = midpoint;
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
