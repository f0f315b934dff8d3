#include "display/gouraud_means.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace radfarm {
namespace {

double TwiceArea(const DisplayMesh& display, const std::array<uint32_t, 3>& v) {
  const Vec3& a = display.positions[v[0]];
  return Length(Cross(display.positions[v[1]] - a, display.positions[v[2]] - a));
}

}  // namespace

std::vector<Rgb> GouraudPatchMeans(const DisplayMesh& display, size_t patches) {
  std::vector<Rgb> sum(patches);
  std::vector<double> area(patches, 0.0);
  for (size_t t = 0; t < display.triangles.size(); ++t) {
    const auto& v = display.triangles[t];
    const double twice_area = TwiceArea(display, v);
    const uint32_t f = display.triangle_patch[t];
    // A linear function's mean over a triangle is the mean of its corner values.
    sum[f] += (display.radiance[v[0]] + display.radiance[v[1]] + display.radiance[v[2]]) *
              (twice_area / 3);
    area[f] += twice_area;
  }
  for (size_t f = 0; f < patches; ++f) sum[f] = area[f] > 0 ? sum[f] / area[f] : Rgb();
  return sum;
}

void StepTowardPatchMeans(DisplayMesh* display, const std::vector<Rgb>& target,
                          const std::vector<bool>& moves, const std::vector<bool>& held) {
  const std::vector<Rgb> shown = GouraudPatchMeans(*display, target.size());
  std::vector<Rgb> sum(display->positions.size());
  std::vector<double> weight(display->positions.size(), 0.0);
  for (size_t t = 0; t < display->triangles.size(); ++t) {
    const auto& v = display->triangles[t];
    const uint32_t f = display->triangle_patch[t];
    const double twice_area = TwiceArea(*display, v);
    const Rgb shortfall = moves[f] ? (target[f] - shown[f]) * twice_area : Rgb();
    for (uint32_t n : v) {
      sum[n] += shortfall;
      weight[n] += twice_area;
    }
  }
  // A dark vertex beside a brighter one (the slit above a hanging lamp) can be pushed below zero
  // by its bright neighbours' shortfall; no light is negative, so it stops at zero.
  for (size_t n = 0; n < sum.size(); ++n) {
    if (weight[n] <= 0 || (!held.empty() && held[n])) continue;
    Rgb& v = display->radiance[n];
    v += sum[n] / weight[n];
    v = {std::max(v.r, 0.0), std::max(v.g, 0.0), std::max(v.b, 0.0)};
  }
}

}  // namespace radfarm
