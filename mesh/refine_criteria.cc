#include "mesh/refine_criteria.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

constexpr double kCornerPull = 0.1;  // corners sampled this far toward the centre

// The sample points of an element: its centre, then its corners pulled inward.
int SamplePoints(const Patch& e, std::array<Vec3, 5>* points) {
  (*points)[0] = e.centre;
  for (int i = 0; i < e.corner_count; ++i) {
    (*points)[i + 1] = e.corners[i] + (e.centre - e.corners[i]) * kCornerPull;
  }
  return e.corner_count + 1;
}

}  // namespace

std::vector<LightSource> StrongestSources(const PatchScene& scene, const std::vector<Rgb>& unshot,
                                          uint32_t limit) {
  std::vector<uint32_t> ids;
  auto power = [&](uint32_t i) { return scene.patches[i].area * unshot[i].Sum(); };
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    if (power(i) > 0) ids.push_back(i);
  }
  const auto stronger = [&](uint32_t a, uint32_t b) {
    const double pa = power(a), pb = power(b);
    return pa != pb ? pa > pb : a < b;
  };
  if (ids.size() > limit) {
    std::nth_element(ids.begin(), ids.begin() + (limit - 1), ids.end(), stronger);
    ids.resize(limit);
  }
  std::sort(ids.begin(), ids.end(), stronger);
  std::vector<LightSource> out;
  for (uint32_t i : ids) {
    const Patch& p = scene.patches[i];
    out.push_back({p.centre, p.normal, p.area, unshot[i], p.surface});
  }
  return out;
}

double LightScore(const Patch& element, const Rgb& radiosity,
                  const std::vector<LightSource>& sources, const std::vector<uint32_t>& surface_of,
                  const RayCaster& caster, double tolerance) {
  if (sources.empty()) return 0;
  std::array<Vec3, 5> points;
  const int n = SamplePoints(element, &points);
  double lo = INFINITY, hi = -INFINITY, sum = 0;
  for (int k = 0; k < n; ++k) {
    Rgb gain;
    for (const LightSource& s : sources) {
      if (s.surface == element.surface) continue;  // a surface does not light itself
      const Vec3 to = s.centre - points[k];
      const double r2 = Dot(to, to);
      if (!(r2 > 0)) continue;
      const Vec3 dir = to / std::sqrt(r2);
      const double cos_e = Dot(dir, element.normal), cos_s = -Dot(dir, s.normal);
      if (cos_e <= 0 || cos_s <= 0) continue;
      const RayHit hit = caster.Trace(points[k], dir, element.normal);
      if (hit.patch == RayHit::kMiss || !hit.front || surface_of[hit.patch] != s.surface) continue;
      const double form_factor = s.area * cos_e * cos_s / (std::numbers::pi * r2 + s.area);
      gain += s.unshot * form_factor;
    }
    const double g = (element.reflectance * gain).Sum();
    lo = std::min(lo, g);
    hi = std::max(hi, g);
    sum += g;
  }
  const double reference = radiosity.Sum() + sum / n;
  return reference > 0 ? (hi - lo) / (tolerance * reference) : 0;
}

double RayNoise(const Patch& patch, const Rgb& radiosity, double ray_power) {
  const Rgb received = radiosity - patch.emission;
  double flux = 0;  // power that arrived: A * (B - E) / rho, per channel
  const double rho[3] = {patch.reflectance.r, patch.reflectance.g, patch.reflectance.b};
  const double gain[3] = {received.r, received.g, received.b};
  for (int c = 0; c < 3; ++c) {
    if (rho[c] > 0 && gain[c] > 0) flux += patch.area * gain[c] / rho[c];
  }
  const double rays = flux / ray_power;
  // A patch no ray has reached yet is as uncertain as its whole value.
  return rays >= 1 ? received.Sum() / std::sqrt(rays) : radiosity.Sum();
}

double GradientScore(const Patch& element, const Rgb& radiosity,
                     const std::vector<Rgb>& vertex_radiance, double ray_power, double tolerance) {
  if (!(ray_power > 0) || !(radiosity.Sum() > 0)) return 0;
  double diff = 0;
  for (const Rgb& v : vertex_radiance) diff = std::max(diff, std::abs(v.Sum() - radiosity.Sum()));
  if (diff <= kNoiseSigmas * RayNoise(element, radiosity, ray_power)) return 0;
  return diff / (tolerance * radiosity.Sum());
}

}  // namespace radfarm
