// DisplayTopology: what the display (display/) needs of a patch mesh, as plain data. The display
// shades "display vertices", one per surface and welded position, so that light never mixes across
// a crease; a patch touches its corners' display vertices and the T-vertices on its edges (where a
// neighbour of the same surface was split differently).
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace radfarm {

struct DisplayTopology {
  // Per display vertex, its position.
  std::vector<Vec3> positions;
  // Per patch, the display vertices at its corners (in the mesh's order around the face) and each
  // corner's own position, which welding may have moved off its display vertex's by a tolerance:
  // patch f's are [corner_begin[f], corner_begin[f + 1]).
  std::vector<uint32_t> corner_begin;
  std::vector<uint32_t> corner_vertex;
  std::vector<Vec3> corner_position;
  // The T-vertices: each a display vertex on the interior of an edge of `patch`, sorted by patch.
  struct EdgeVertex {
    uint32_t patch;
    uint32_t vertex;
  };
  std::vector<EdgeVertex> edge_vertices;
  // Per patch, its display vertices around it in patch corner order (Patch::corners), the
  // T-vertices between the corners they lie between: the outline its display triangles fill.
  std::vector<std::vector<uint32_t>> rings;

  size_t patch_count() const { return rings.size(); }
  size_t vertex_count() const { return positions.size(); }

  // visit(display vertex, patch) for every patch touching a display vertex: all corners patch by
  // patch, then the T-vertices. Sums over it are taken in this one order, so they are the same
  // bits however the display is run.
  template <typename Visit>
  void ForEachVertexPatch(Visit&& visit) const {
    for (uint32_t f = 0; f + 1 < corner_begin.size(); ++f) {
      for (uint32_t k = corner_begin[f]; k < corner_begin[f + 1]; ++k) visit(corner_vertex[k], f);
    }
    for (const EdgeVertex& e : edge_vertices) visit(e.vertex, e.patch);
  }
};

}  // namespace radfarm
