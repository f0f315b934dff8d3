#include "mesh/triangle_edges.h"

#include <algorithm>

namespace radfarm {

TriangleEdges IndexEdges(const std::vector<std::array<uint32_t, 3>>& triangles, size_t vertices) {
  // Every side, bucketed by its lower vertex (a counting sort), then within a bucket (a vertex's
  // few sides) sorted by the other vertex and the side's position.
  const size_t sides = 3 * triangles.size();
  std::vector<uint32_t> bucket_start(vertices + 1, 0);
  for (const auto& v : triangles) {
    for (int k = 0; k < 3; ++k) ++bucket_start[std::min(v[k], v[(k + 1) % 3]) + 1];
  }
  for (size_t i = 0; i < vertices; ++i) bucket_start[i + 1] += bucket_start[i];
  struct Side {
    uint32_t other;  // the higher vertex
    uint32_t slot;   // 3 t + k
  };
  std::vector<Side> bucketed(sides);
  std::vector<uint32_t> fill(bucket_start.begin(), bucket_start.end() - 1);
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    const auto& v = triangles[t];
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      bucketed[fill[std::min(a, b)]++] = {std::max(a, b), 3 * t + k};
    }
  }
  TriangleEdges out;
  out.edge_of.resize(sides);
  out.sides.reserve(sides);
  for (size_t i = 0; i < vertices; ++i) {
    const auto begin = bucketed.begin() + bucket_start[i],
               end = bucketed.begin() + bucket_start[i + 1];
    std::sort(begin, end, [](const Side& x, const Side& y) {
      return x.other != y.other ? x.other < y.other : x.slot < y.slot;
    });
    for (auto s = begin; s != end; ++s) {
      if (s == begin || s->other != (s - 1)->other) {
        out.first.push_back(static_cast<uint32_t>(out.sides.size()));
      }
      out.edge_of[s->slot] = static_cast<uint32_t>(out.first.size() - 1);
      out.sides.push_back(s->slot / 3);
    }
  }
  out.first.push_back(static_cast<uint32_t>(out.sides.size()));
  return out;
}

}  // namespace radfarm
