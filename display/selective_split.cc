#include "display/selective_split.h"

#include "mesh/triangle_edges.h"

namespace radfarm {

SelectiveSplit SplitMarked(const DisplayMesh& mesh, std::vector<bool> marked) {
  const size_t triangles = mesh.triangles.size();
  marked.resize(triangles, false);
  // The triangles on each edge, to spread the marks until no unmarked triangle has two cut edges.
  const TriangleEdges edges = IndexEdges(mesh.triangles, mesh.positions.size());
  std::vector<uint8_t> cut_edges(triangles, 0);
  std::vector<uint32_t> queue;
  for (uint32_t t = 0; t < triangles; ++t) {
    if (marked[t]) queue.push_back(t);
  }
  std::vector<bool> cut(edges.edges(), false);
  while (!queue.empty()) {
    const uint32_t t = queue.back();
    queue.pop_back();
    for (int k = 0; k < 3; ++k) {
      const uint32_t e = edges.edge_of[3 * t + k];
      if (cut[e]) continue;
      cut[e] = true;
      for (uint32_t s = edges.first[e]; s < edges.first[e + 1]; ++s) {
        const uint32_t other = edges.sides[s];
        if (other == t || marked[other]) continue;
        if (++cut_edges[other] >= 2) {
          marked[other] = true;
          queue.push_back(other);
        }
      }
    }
  }

  SelectiveSplit out;
  out.first_new = static_cast<uint32_t>(mesh.positions.size());
  DisplayMesh& fine = out.mesh;
  fine.positions = mesh.positions;
  fine.radiance = mesh.radiance;
  fine.radiance.resize(mesh.positions.size());
  fine.patch_front_only = mesh.patch_front_only;
  constexpr uint32_t kNone = ~uint32_t{0};
  std::vector<uint32_t> midpoint_of_edge(edges.edges(), kNone);
  // The midpoint of side k of triangle t, made when first asked for.
  auto midpoint = [&](size_t t, int k) {
    uint32_t& m = midpoint_of_edge[edges.edge_of[3 * t + k]];
    if (m == kNone) {
      const uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      m = static_cast<uint32_t>(fine.positions.size());
      fine.positions.push_back((fine.positions[a] + fine.positions[b]) * 0.5);
      fine.radiance.push_back((fine.radiance[a] + fine.radiance[b]) * 0.5);
      out.edge_ends.push_back({a, b});
    }
    return m;
  };
  for (size_t t = 0; t < triangles; ++t) {
    const std::array<uint32_t, 3>& v = mesh.triangles[t];
    const uint32_t patch = mesh.triangle_patch[t];
    auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
      fine.triangles.push_back({a, b, c});
      fine.triangle_patch.push_back(patch);
    };
    if (marked[t]) {
      const uint32_t m0 = midpoint(t, 0), m1 = midpoint(t, 1), m2 = midpoint(t, 2);
      add(v[0], m0, m2);
      add(m0, v[1], m1);
      add(m2, m1, v[2]);
      add(m0, m1, m2);
      continue;
    }
    int k = 0;
    while (k < 3 && !cut[edges.edge_of[3 * t + k]]) ++k;
    if (k == 3) {
      add(v[0], v[1], v[2]);
      continue;
    }
    // One cut edge (v[k], v[k + 1]): two triangles through its midpoint, turning as this one does.
    const uint32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    const uint32_t m = midpoint(t, k);
    add(a, m, c);
    add(m, b, c);
  }
  return out;
}

}  // namespace radfarm
