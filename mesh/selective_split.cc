#include "mesh/selective_split.h"

#include <algorithm>
#include <unordered_map>

namespace radfarm {
namespace {

uint64_t EdgeKey(uint32_t a, uint32_t b) { return uint64_t{std::min(a, b)} << 32 | std::max(a, b); }

}  // namespace

SelectiveSplit SplitMarked(const DisplayMesh& mesh, std::vector<bool> marked) {
  const size_t triangles = mesh.triangles.size();
  marked.resize(triangles, false);
  // The triangles on each edge, to spread the marks until no unmarked triangle has two cut edges.
  std::unordered_map<uint64_t, std::vector<uint32_t>> on_edge;
  on_edge.reserve(2 * triangles);
  for (uint32_t t = 0; t < triangles; ++t) {
    const auto& v = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) on_edge[EdgeKey(v[k], v[(k + 1) % 3])].push_back(t);
  }
  std::vector<uint8_t> cut_edges(triangles, 0);
  std::vector<uint32_t> queue;
  for (uint32_t t = 0; t < triangles; ++t) {
    if (marked[t]) queue.push_back(t);
  }
  std::unordered_map<uint64_t, bool> cut;
  while (!queue.empty()) {
    const uint32_t t = queue.back();
    queue.pop_back();
    const auto& v = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const uint64_t key = EdgeKey(v[k], v[(k + 1) % 3]);
      if (!cut.emplace(key, true).second) continue;
      for (uint32_t other : on_edge[key]) {
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
  std::unordered_map<uint64_t, uint32_t> midpoint_of_edge;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    const auto [it, added] =
        midpoint_of_edge.try_emplace(EdgeKey(a, b), static_cast<uint32_t>(fine.positions.size()));
    if (added) {
      fine.positions.push_back((fine.positions[a] + fine.positions[b]) * 0.5);
      fine.radiance.push_back((fine.radiance[a] + fine.radiance[b]) * 0.5);
      out.edge_ends.push_back({a, b});
    }
    return it->second;
  };
  for (size_t t = 0; t < triangles; ++t) {
    const std::array<uint32_t, 3>& v = mesh.triangles[t];
    const uint32_t patch = mesh.triangle_patch[t];
    auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
      fine.triangles.push_back({a, b, c});
      fine.triangle_patch.push_back(patch);
    };
    if (marked[t]) {
      const uint32_t m0 = midpoint(v[0], v[1]), m1 = midpoint(v[1], v[2]),
                     m2 = midpoint(v[2], v[0]);
      add(v[0], m0, m2);
      add(m0, v[1], m1);
      add(m2, m1, v[2]);
      add(m0, m1, m2);
      continue;
    }
    int k = 0;
    while (k < 3 && !cut.count(EdgeKey(v[k], v[(k + 1) % 3]))) ++k;
    if (k == 3) {
      add(v[0], v[1], v[2]);
      continue;
    }
    // One cut edge (v[k], v[k + 1]): two triangles through its midpoint, turning as this one does.
    const uint32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
    const uint32_t m = midpoint(a, b);
    add(a, m, c);
    add(m, b, c);
  }
  return out;
}

}  // namespace radfarm
