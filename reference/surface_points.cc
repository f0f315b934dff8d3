#include "reference/surface_points.h"

#include <algorithm>
#include <cmath>

#include "core/counter_rng.h"

namespace radfarm::reference {

namespace {

// Point i of the area-uniform sequence of `seed`.
class AreaSampler {
 public:
  explicit AreaSampler(const ReferenceScene& scene) : scene_(scene) {
    for (const Triangle& t : scene.triangles()) cdf_.push_back(total_ += t.area);
  }
  SurfacePoint Point(uint64_t seed, uint64_t i) const {
    const std::vector<Triangle>& tris = scene_.triangles();
    const CounterRng rng(HashWords(seed, 0x5eed901a7ULL, i));
    const double u = rng.Uniform(0) * total_;
    const size_t k = std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(),
                                      tris.size() - 1);
    const Triangle& t = tris[k];
    const double s = std::sqrt(rng.Uniform(1));
    const double v = rng.Uniform(2);
    const bool back = scene_.materials()[t.material].two_sided && rng.Uniform(3) < 0.5;
    return {t.a + t.ab * (s * (1 - v)) + t.ac * (s * v), back ? -t.normal : t.normal, uint32_t(k)};
  }

 private:
  const ReferenceScene& scene_;
  std::vector<double> cdf_;
  double total_ = 0;
};

}  // namespace

SurfaceHit NearestSurfaceWithin(const ReferenceScene& scene, const SurfacePoint& point,
                                double band) {
  Vec3 t, b;
  OrthonormalBasis(point.normal, &t, &b);
  SurfaceHit nearest;
  double nearest_distance = band;
  for (uint32_t k = 0; k < kBandProbes; ++k) {
    // A fixed, evenly spread set: a spiral over the hemisphere, uniform in solid angle.
    const double z = 1 - (k + 0.5) / kBandProbes;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    const double phi = 2.399963229728653 * k;  // the golden angle
    const Vec3 d = t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + point.normal * z;
    const SurfaceHit hit = scene.Trace(point.position, d, point.normal);
    if (hit.triangle == SurfaceHit::kMiss) continue;
    const double distance = Length(hit.position - point.position);
    if (distance < nearest_distance) {
      nearest = hit;
      nearest_distance = distance;
    }
  }
  return nearest;
}

bool NearAnotherSurface(const ReferenceScene& scene, const SurfacePoint& point, double band) {
  return NearestSurfaceWithin(scene, point, band).triangle != SurfaceHit::kMiss;
}

std::vector<SurfacePoint> SampleBandPoints(const ReferenceScene& scene, uint32_t count,
                                           uint64_t seed, double band, uint64_t max_candidates) {
  const AreaSampler sampler(scene);
  std::vector<SurfacePoint> points;
  for (uint64_t i = 0; i < max_candidates && points.size() < count; ++i) {
    const SurfacePoint p = sampler.Point(HashWords(seed, 0xba4d), i);
    if (NearAnotherSurface(scene, p, band)) points.push_back(p);
  }
  return points;
}

std::vector<SurfacePoint> SampleSurfacePoints(const ReferenceScene& scene, uint32_t count,
                                              uint64_t seed) {
  const AreaSampler sampler(scene);
  std::vector<SurfacePoint> points;
  for (uint32_t i = 0; i < count; ++i) points.push_back(sampler.Point(seed, i));
  return points;
}

}  // namespace radfarm::reference
