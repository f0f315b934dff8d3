#include "bench/reference/surface_points.h"

#include <algorithm>
#include <cmath>

#include "core/counter_rng.h"

namespace radfarm::reference {

std::vector<SurfacePoint> SampleSurfacePoints(const ReferenceScene& scene, uint32_t count,
                                              uint64_t seed) {
  const std::vector<Triangle>& tris = scene.triangles();
  std::vector<double> cdf;
  double total = 0;
  for (const Triangle& t : tris) cdf.push_back(total += t.area);
  std::vector<SurfacePoint> points;
  for (uint32_t i = 0; i < count; ++i) {
    const CounterRng rng(HashWords(seed, 0x5eed901a7ULL, i));
    const double u = rng.Uniform(0) * total;
    const size_t k = std::min<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin(),
                                      tris.size() - 1);
    const Triangle& t = tris[k];
    const double s = std::sqrt(rng.Uniform(1));
    const double v = rng.Uniform(2);
    const bool back = scene.materials()[t.material].two_sided && rng.Uniform(3) < 0.5;
    points.push_back(
        {t.a + t.ab * (s * (1 - v)) + t.ac * (s * v), back ? -t.normal : t.normal, uint32_t(k)});
  }
  return points;
}

}  // namespace radfarm::reference
