#include "bench/refine/solution_error.h"

#include <algorithm>
#include <cmath>

#include "mesh/locate_patches.h"

namespace radfarm::bench {
namespace {

constexpr int kSections = 4;  // points per element: kSections^2
constexpr int kPointsPerElement = kSections * kSections;

// kSections^2 points of equal share over a patch: the centres of a kSections x kSections grid of
// a quad (bilinear), the centroids of the kSections^2 triangles of a triangle cut into sections.
void AppendElementPoints(const Patch& p, std::vector<SurfacePoint>* out) {
  const auto& c = p.corners;
  if (p.corner_count == 4) {
    for (int i = 0; i < kSections; ++i) {
      for (int j = 0; j < kSections; ++j) {
        const double u = (i + 0.5) / kSections, v = (j + 0.5) / kSections;
        out->push_back({c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * (u * v) +
                            c[3] * ((1 - u) * v),
                        p.normal});
      }
    }
    return;
  }
  auto at = [&](double u, double v) { return c[0] * (1 - u - v) + c[1] * u + c[2] * v; };
  for (int i = 0; i < kSections; ++i) {
    for (int j = 0; i + j < kSections; ++j) {
      out->push_back({at((i + 1.0 / 3) / kSections, (j + 1.0 / 3) / kSections), p.normal});
      if (i + j < kSections - 1) {
        out->push_back({at((i + 2.0 / 3) / kSections, (j + 2.0 / 3) / kSections), p.normal});
      }
    }
  }
}

}  // namespace

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
