// The edges of a triangle list and the triangles on each, for the display's splits
// (midpoint_split.h, selective_split.h): flat arrays built in linear time, where a hash map of
// edges cost most of a split on a big display.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace radfarm {

struct TriangleEdges {
  // Per triangle t and side k (from corner k to corner k + 1), at 3 t + k: its edge's id.
  std::vector<uint32_t> edge_of;
  // The triangles on edge e: sides[first[e]] .. sides[first[e + 1] - 1], in increasing order
  // (a triangle once per side it has on the edge).
  std::vector<uint32_t> first;
  std::vector<uint32_t> sides;
  size_t edges() const { return first.empty() ? 0 : first.size() - 1; }
};

// Two sides share an edge when they join the same two vertices, either way round. `vertices`: one
// more than the largest index used.
TriangleEdges IndexEdges(const std::vector<std::array<uint32_t, 3>>& triangles, size_t vertices);

}  // namespace radfarm
