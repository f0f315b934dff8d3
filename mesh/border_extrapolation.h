// Vertex radiance at the border of a surface. Averaging the patches around a vertex puts a border
// vertex at the mean of the patches beside it: the value half a patch inside the surface. Where
// light falls off toward a crease (every corner of a room), each border is then drawn too bright by
// the drop over half a patch: a bright band along every crease, wider the coarser the patches.
// A border vertex instead continues the gradient across the patches beside it: B = 2 A - I, with A
// its average and I the mean of the averages of its neighbours inside the surface. Along a grid of
// equal patches carrying a linear field this is the field's value at the border exactly (A is the
// field half a patch in, I one patch in). A border vertex with no neighbour inside the surface (the
// corner of a grid) keeps its average; extrapolated channels are clamped at 0. The price is noise:
// a border vertex's value combines fewer, differently weighted patches; the image's error drops
// all the same (docs/BENCHMARKS-adaptive.md).
#pragma once

#include <cstdint>
#include <vector>

#include "core/rgb.h"

namespace radfarm {

// `rings[f]` lists the display vertices around face f in order (corners and the T-vertices on its
// edges), all of one surface; an edge of a ring that no other ring has is on the surface's border.
// `values` holds one averaged radiance per display vertex and is updated in place.
void ExtrapolateBorders(const std::vector<std::vector<uint32_t>>& rings, std::vector<Rgb>* values);

}  // namespace radfarm
