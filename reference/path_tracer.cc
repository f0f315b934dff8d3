#include "reference/path_tracer.h"

#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>

#include "core/counter_rng.h"
#include "core/punctual_light.h"
#include "core/sky.h"

namespace radfarm::reference {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kDimsPerBounce = 8;
constexpr int kRouletteDepth = 2;  // bounces before Russian roulette starts

double Uniform(uint64_t key, uint32_t dim) { return CounterRng(key).Uniform(dim); }

Vec3 CosineDirection(const Vec3& n, double u1, double u2) {
  Vec3 t, b;
  OrthonormalBasis(n, &t, &b);
  const double r = std::sqrt(u1);
  const double phi = 2 * kPi * u2;
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - u1));
}

Vec3 PointOn(const Triangle& tri, double u1, double u2) {
  const double s = std::sqrt(u1);
  return tri.a + tri.ab * (s * (1 - u2)) + tri.ac * (s * u2);
}

}  // namespace

Rgb PathTracer::Emitted(uint32_t triangle, bool front) const {
  const Material& m = scene_.materials()[scene_.triangles()[triangle].material];
  return front || m.two_sided ? m.emission : Rgb{};
}

Rgb PathTracer::SampleEmitters(const Vec3& x, const Vec3& n, uint32_t self, uint64_t key,
                               uint32_t dim, uint64_t* rays) const {
  if (scene_.emitters().empty()) return {};
  const ReferenceScene::Emitter& e = scene_.PickEmitter(Uniform(key, dim));
  if (e.triangle == self) return {};
  const Triangle& tri = scene_.triangles()[e.triangle];
  const Vec3 y = PointOn(tri, Uniform(key, dim + 1), Uniform(key, dim + 2));
  const Vec3 d = y - x;
  const double dist2 = Dot(d, d);
  if (!(dist2 > 0)) return {};
  const Vec3 w = d / std::sqrt(dist2);
  const double cos_x = Dot(n, w);
  const double signed_cos_y = -Dot(tri.normal, w);
  const bool front = signed_cos_y > 0;
  const double cos_y = std::abs(signed_cos_y);
  const Rgb le = Emitted(e.triangle, front);
  if (cos_x <= 0 || cos_y <= 0 || le.Sum() <= 0) return {};
  ++*rays;
  if (!scene_.Unoccluded(x, y, n)) return {};
  const double pdf_light = e.probability / tri.area * dist2 / cos_y;  // per solid angle
  const double pdf_bsdf = cos_x / kPi;
  const double weight = pdf_light / (pdf_light + pdf_bsdf);
  // The BRDF's 1/pi times cos_x over the light's pdf; rho is in the path's throughput.
  return le * (weight * cos_x / (kPi * pdf_light));
}

Rgb PathTracer::PunctualIrradiance(const Vec3& x, const Vec3& n, uint64_t* rays) const {
  Rgb sum;
  for (const PunctualLight& light : scene_.lights()) {
    const Rgb e = UnshadowedIrradiance(light, x, n);
    if (e.Sum() <= 0) continue;
    ++*rays;
    if (scene_.Unoccluded(x, ShadowRayTarget(light, x, 4 * scene_.diagonal() + 1), n)) sum += e;
  }
  return sum;
}

Rgb PathTracer::SamplePath(Vec3 x, Vec3 n, uint32_t self, Rgb beta, uint64_t key,
                           uint64_t* rays) const {
  Rgb sum;
  for (int depth = 0; beta.Max() > 0; ++depth) {
    const uint32_t dim = uint32_t(depth) * kDimsPerBounce;
    sum += beta * SampleEmitters(x, n, self, key, dim, rays);
    if (!scene_.lights().empty()) sum += beta * PunctualIrradiance(x, n, rays);
    const Vec3 w = CosineDirection(n, Uniform(key, dim + 3), Uniform(key, dim + 4));
    ++*rays;
    const SurfaceHit hit = scene_.Trace(x, w, n);
    if (hit.triangle == SurfaceHit::kMiss) {
      // The cosine-weighted direction's estimate of rho/pi * L cos / pdf is rho * L.
      sum += beta * SkyRadiance(scene_.sky(), w);
      break;
    }
    const Triangle& tri = scene_.triangles()[hit.triangle];
    const Material& m = scene_.materials()[tri.material];
    if (!hit.front && !m.two_sided) break;  // a one-sided surface's back absorbs
    const Vec3 hn = hit.front ? tri.normal : -tri.normal;
    const double p_emitter = scene_.EmitterProbability(hit.triangle);
    if (p_emitter > 0) {
      const Vec3 d = hit.position - x;
      const double cos_y = -Dot(hn, w);
      const double cos_x = Dot(n, w);
      if (cos_y > 0 && cos_x > 0) {
        const double pdf_light = p_emitter / tri.area * Dot(d, d) / cos_y;
        const double pdf_bsdf = cos_x / kPi;
        // The cosine-weighted direction's estimate of rho/pi * Le cos / pdf is rho * Le.
        sum += beta * Emitted(hit.triangle, hit.front) * (pdf_bsdf / (pdf_light + pdf_bsdf));
      }
    }
    beta = beta * m.diffuse;
    if (depth >= kRouletteDepth) {
      const double survive = std::min(0.95, beta.Max());
      if (Uniform(key, dim + 5) >= survive) break;
      beta = beta / survive;
    }
    x = hit.position;
    n = hn;
    self = hit.triangle;
  }
  return sum;
}

template <typename Sample>
PointEstimate PathTracer::Accumulate(const Rgb& own, uint64_t index, const TraceSettings& settings,
                                     const Sample& sample) const {
  Rgb sum, sum2;
  double total_sum = 0, total_sum2 = 0;  // the channel sum's, for the relative error
  PointEstimate out;
  const uint64_t block = std::max<uint64_t>(1, settings.block);
  while (out.samples < settings.max_samples) {
    const uint64_t end = std::min(settings.max_samples, out.samples + block);
    for (uint64_t s = out.samples; s < end; ++s) {
      const Rgb v = sample(HashWords(settings.seed, index, s), &out.rays);
      sum += v;
      sum2 += v * v;
      total_sum += v.Sum();
      total_sum2 += v.Sum() * v.Sum();
    }
    out.samples = end;
    const double n = double(out.samples);
    auto standard_error = [n](double s, double s2) {
      const double mean = s / n;
      return std::sqrt(std::max(0.0, (s2 / n - mean * mean) / std::max(1.0, n - 1)));
    };
    out.radiance = own + sum / n;
    out.standard_error = {standard_error(sum.r, sum2.r), standard_error(sum.g, sum2.g),
                          standard_error(sum.b, sum2.b)};
    const double total = out.radiance.Sum();
    out.relative_error = total > 0 ? standard_error(total_sum, total_sum2) / total : 0;
    if (out.samples >= settings.min_samples && out.relative_error <= settings.relative_error) {
      break;
    }
  }
  return out;
}

PointEstimate PathTracer::Estimate(const SurfacePoint& point, uint64_t index,
                                   const TraceSettings& settings) const {
  const Triangle& tri = scene_.triangles()[point.triangle];
  const bool front = Dot(point.normal, tri.normal) > 0;
  const Rgb rho = scene_.materials()[tri.material].diffuse;
  return Accumulate(
      Emitted(point.triangle, front), index, settings, [&](uint64_t key, uint64_t* rays) {
        return SamplePath(point.position, point.normal, point.triangle, rho, key, rays);
      });
}

PointEstimate PathTracer::EstimateIrradiance(const Vec3& position, const Vec3& normal,
                                             uint64_t index, const TraceSettings& settings) const {
  return Accumulate({}, index, settings, [&](uint64_t key, uint64_t* rays) {
    return SamplePath(position, normal, SurfaceHit::kMiss, {1, 1, 1}, key, rays);
  });
}

std::vector<PointEstimate> PathTracer::EstimateIrradianceAll(const std::vector<Vec3>& positions,
                                                             const std::vector<Vec3>& normals,
                                                             const TraceSettings& settings) const {
  std::vector<PointEstimate> out(positions.size());
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next++; i < positions.size(); i = next++) {
      out[i] = EstimateIrradiance(positions[i], normals[i], i, settings);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned t = 1; t < std::max(1u, settings.threads); ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return out;
}

std::vector<PointEstimate> PathTracer::EstimateAll(const std::vector<SurfacePoint>& points,
                                                   const TraceSettings& settings) const {
  std::vector<PointEstimate> out(points.size());
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next++; i < points.size(); i = next++)
      out[i] = Estimate(points[i], i, settings);
  };
  std::vector<std::thread> threads;
  for (unsigned t = 1; t < std::max(1u, settings.threads); ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return out;
}

Result<SurfacePoint> LocatePoint(const ReferenceScene& scene, const Vec3& p, const Vec3& n) {
  const double h = scene.diagonal() * 1e-4;
  const SurfaceHit hit = scene.Trace(p + n * h, -n, n);
  if (hit.triangle != SurfaceHit::kMiss) {
    const Triangle& tri = scene.triangles()[hit.triangle];
    const bool two_sided = scene.materials()[tri.material].two_sided;
    if (Length(hit.position - p) <= 2 * h && (hit.front || two_sided)) {
      return SurfacePoint{hit.position, hit.front ? tri.normal : -tri.normal, hit.triangle};
    }
  }
  return Error{"no surface faces the normal at the point"};
}

}  // namespace radfarm::reference
