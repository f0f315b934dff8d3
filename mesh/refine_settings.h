// Settings of adaptive refinement (refine.h): the job file's mesh.refine* keys.
#pragma once

#include <cstdint>

namespace radfarm {

struct RefineSettings {
  bool enabled = false;
  // An element splits when the Gouraud image would miss the light still to arrive, or its own
  // radiance, by more than this fraction of its radiance (and, for the radiance, more than the ray
  // noise). 0.1: docs/BENCHMARKS-adaptive.md.
  double tolerance = 0.1;
  // No element edge shorter than this, in scene units; 0: the patch size / 4.
  double min_element_size = 0;
  // Refinement stops at this many elements; 0: 8 times the initial patch count.
  uint64_t max_elements = 0;
};

}  // namespace radfarm
