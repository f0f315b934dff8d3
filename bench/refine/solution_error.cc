#include "bench/refine/solution_error.h"

#include <algorithm>
#include <cmath>

#include "bench/refine/element_points.h"
#include "mesh/locate_patches.h"

namespace radfarm::bench {

PatchError MeasurePatchError(const PatchScene& run, const std::vector<Rgb>& radiosity,
                             const ReferenceSolution& ref) {
  std::vector<SurfacePoint> points;
  points.reserve(run.patches.size() * kPointsPerElement);
  for (const Patch& p : run.patches) AppendElementPoints(p, &points);
  const std::vector<uint32_t> under = LocatePoints(ref.scene, points);
  PatchError out;
  const double threshold = ref.dark_threshold;
  const size_t n = run.patches.size();
  std::vector<double> bref(n, 0), noise(n, 0);
  std::vector<bool> counted(n, true);
  for (size_t e = 0; e < n; ++e) {
    for (int k = 0; k < kPointsPerElement; ++k) {
      const uint32_t r = under[e * kPointsPerElement + k];
      if (r == kNoPatch || !(ref.mean[r] >= threshold)) {
        counted[e] = false;
        break;
      }
      bref[e] += ref.mean[r] / kPointsPerElement;
      noise[e] += ref.half_diff[r] / kPointsPerElement;
    }
  }
  double area = 0, sq = 0, sq_noise = 0;
  for (size_t e = 0; e < n; ++e) {
    if (!counted[e]) continue;
    const double a = run.patches[e].area;
    const double rel = (radiosity[e].Sum() - bref[e]) / bref[e];
    const double rel_noise = noise[e] / bref[e];
    area += a;
    sq += a * rel * rel;
    sq_noise += a * rel_noise * rel_noise;
  }
  if (!(area > 0)) return out;
  out.measured = std::sqrt(sq / area);
  out.reference_noise = std::sqrt(sq_noise / area);
  out.net = std::sqrt(std::max(0.0, sq - sq_noise) / area);
  return out;
}

double MeasureImageError(const Image& image, const ReferenceSolution& ref) {
  double sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    sum += std::abs(image.pixels[i].Sum() - ref.image.pixels[i].Sum());
  }
  return sum / double(image.pixels.size()) / ref.image_mean;
}

}  // namespace radfarm::bench
