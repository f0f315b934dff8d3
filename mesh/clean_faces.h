// First meshing step: the input faces as cleaned polygons (no repeated or straight-through corners)
// with their normal and area, and the degenerate ones set aside.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "input/input_scene.h"

namespace radfarm {

struct CleanFace {
  std::vector<Vec3> corners;  // counter-clockwise about normal, at least 3
  Vec3 normal;                // unit, the Newell normal (best plane of a non-planar face)
  double area = 0;            // length of the Newell vector area
  uint32_t material = 0;
  uint32_t line = 0;    // of the `f` statement, for messages
  uint32_t object = 0;  // InputFace::object
};

struct CleanFaces {
  std::vector<CleanFace> faces;
  std::vector<uint32_t> degenerate_lines;  // faces dropped: fewer than 3 distinct corners after
                                           // merging within tol, all collinear, or area < min_area
};

// Indices must be in range (checked by the caller).
CleanFaces CleanInputFaces(const InputScene& scene, double tol, double min_area);

}  // namespace radfarm
