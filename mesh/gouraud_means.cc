#include "mesh/gouraud_means.h"

namespace radfarm {

std::vector<Rgb> GouraudPatchMeans(const DisplayMesh& display, size_t patches) {
  std::vector<Rgb> sum(patches);
  std::vector<double> area(patches, 0.0);
  for (size_t t = 0; t < display.triangles.size(); ++t) {
    const auto& v = display.triangles[t];
    const Vec3& a = display.positions[v[0]];
    const double twice_area =
        Length(Cross(display.positions[v[1]] - a, display.positions[v[2]] - a));
    const uint32_t f = display.triangle_patch[t];
    // A linear function's mean over a triangle is the mean of its corner values.
    sum[f] += (display.radiance[v[0]] + display.radiance[v[1]] + display.radiance[v[2]]) *
              (twice_area / 3);
    area[f] += twice_area;
  }
  for (size_t f = 0; f < patches; ++f) sum[f] = area[f] > 0 ? sum[f] / area[f] : Rgb();
  return sum;
}

}  // namespace radfarm
