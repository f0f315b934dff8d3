#include "bench/refine/element_points.h"

namespace radfarm::bench {

void AppendElementPoints(const Patch& p, std::vector<SurfacePoint>* out) {
  const auto& c = p.corners;
  if (p.corner_count == 4) {
    for (int i = 0; i < kElementPointSections; ++i) {
      for (int j = 0; j < kElementPointSections; ++j) {
        const double u = (i + 0.5) / kElementPointSections, v = (j + 0.5) / kElementPointSections;
        out->push_back({c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * (u * v) +
                            c[3] * ((1 - u) * v),
                        p.normal});
      }
    }
    return;
  }
  auto at = [&](double u, double v) { return c[0] * (1 - u - v) + c[1] * u + c[2] * v; };
  for (int i = 0; i < kElementPointSections; ++i) {
    for (int j = 0; i + j < kElementPointSections; ++j) {
      out->push_back(
          {at((i + 1.0 / 3) / kElementPointSections, (j + 1.0 / 3) / kElementPointSections),
           p.normal});
      if (i + j < kElementPointSections - 1) {
        out->push_back(
            {at((i + 2.0 / 3) / kElementPointSections, (j + 2.0 / 3) / kElementPointSections),
             p.normal});
      }
    }
  }
}

}  // namespace radfarm::bench
