// The reference every row of the adaptive report is measured against: a uniform mesh as fine as
// the adaptive runs' smallest elements, solved twice with many rays and different seeds. Their
// mean is the reference; half their difference estimates its own noise, so a row's error can be
// told apart from the reference's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "input/input_scene.h"
#include "output/camera.h"
#include "output/image.h"

namespace radfarm::bench {

inline constexpr double kLitFraction = 0.01;

struct ReferenceSolution {
  double patch_size = 0;
  PatchScene scene;
  // PatchMesh::covered_surfaces: the same ids in every mesh of the scene.
  std::vector<uint32_t> covered_surfaces;
  std::vector<double> mean;  // per reference patch: the two solves' mean radiosity (channel sum)
  std::vector<double> half_diff;  // per reference patch: half their difference
  // per reference patch: `mean` less rho times its direct light (BouncedRadiosity), channel sum
  std::vector<double> bounced;
  // kLitFraction of the median positive `mean`: patches below it are dark (behind a light, under
  // a block).
  double dark_threshold = 0;
  Image image;             // RenderReferenceImage of the mean solution
  Image bounced_image;     // its Gouraud-shaded part: `image` less it is the direct light
  double image_mean = 0;   // mean pixel value (channel sum)
  uint64_t shot_rays = 0;  // of each solve
  uint64_t rays = 0;       // both solves
  double seconds = 0;      // both solves
};

// With `cache_dir` set, the solves' results are kept there (keyed by scene name, patch size, ray
// count and camera size) and read back by the next run instead of solving again.
ReferenceSolution SolveReference(const InputScene& scene, const std::string& name,
                                 double patch_size, uint64_t shot_rays, const Camera& camera,
                                 const std::string& cache_dir);

}  // namespace radfarm::bench
