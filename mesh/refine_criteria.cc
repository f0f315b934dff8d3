#include "mesh/refine_criteria.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace radfarm {
namespace {

constexpr double kCornerPull = 0.1;  // points sampled this far toward the centre

Vec3 Pulled(const Patch& e, const Vec3& p) { return p + (e.centre - p) * kCornerPull; }

// The centres of four equal parts of a patch: the quarters of a parallelogram-like quad by its
// bilinear midlines, the corner triangles of a triangle cut at its edge midpoints.
std::array<Vec3, kSourceSamples> SourceSamples(const Patch& p) {
  const auto& c = p.corners;
  if (p.corner_count == 4) {
    auto at = [&](double u, double v) {
      return c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * (u * v) +
             c[3] * ((1 - u) * v);
    };
    return {at(0.25, 0.25), at(0.75, 0.25), at(0.75, 0.75), at(0.25, 0.75)};
  }
  const Vec3 m01 = (c[0] + c[1]) * 0.5, m12 = (c[1] + c[2]) * 0.5, m20 = (c[2] + c[0]) * 0.5;
  auto centroid = [](const Vec3& a, const Vec3& b, const Vec3& d) { return (a + b + d) / 3.0; };
  return {centroid(c[0], m01, m20), centroid(m01, c[1], m12), centroid(m20, m12, c[2]),
          centroid(m01, m12, m20)};
}

// The reflected gain the sources will bring to `point` of `element` (channel sum).
double Gain(const Patch& element, const Vec3& point, const std::vector<LightSource>& sources,
            const std::vector<uint32_t>& surface_of, const RayCaster& caster) {
  Rgb gain;
  for (const LightSource& s : sources) {
    if (s.surface == element.surface) continue;  // a surface does not light itself
    for (const Vec3& sample : s.samples) {
      const Vec3 to = sample - point;
      const double r2 = Dot(to, to);
      if (!(r2 > 0)) continue;
      const Vec3 dir = to / std::sqrt(r2);
      const double cos_e = Dot(dir, element.normal), cos_s = -Dot(dir, s.normal);
      if (cos_e <= 0 || cos_s <= 0) continue;
      const RayHit hit = caster.Trace(point, dir, element.normal);
      if (hit.patch == RayHit::kMiss || !hit.front || surface_of[hit.patch] != s.surface) continue;
      gain += s.unshot * (s.sample_area * cos_e * cos_s / (std::numbers::pi * r2 + s.sample_area));
    }
  }
  return (element.reflectance * gain).Sum();
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
    out.push_back({SourceSamples(p), p.normal, p.area / kSourceSamples, unshot[i], p.surface});
  }
  return out;
}

double LightScore(const Patch& element, const Rgb& radiosity,
                  const std::vector<LightSource>& sources, const std::vector<uint32_t>& surface_of,
                  const RayCaster& caster, double tolerance) {
  if (sources.empty()) return 0;
  // A lattice of kLattice + 1 points per edge over the element; the image interpolates the corner
  // values (bilinearly over a quad, barycentrically over a triangle), so every other lattice point
  // checks that interpolation. Three sections per edge catch a penumbra narrower than the element
  // wherever it crosses.
  constexpr int kLattice = 3;
  const auto& c = element.corners;
  const bool quad = element.corner_count == 4;
  std::array<double, 4> corner{};
  for (int k = 0; k < element.corner_count; ++k) {
    corner[k] = Gain(element, Pulled(element, c[k]), sources, surface_of, caster);
  }
  double worst = 0, sum = 0;
  int points = 0;
  for (int i = 0; i <= kLattice; ++i) {
    for (int j = 0; j <= (quad ? kLattice : kLattice - i); ++j) {
      const double u = double(i) / kLattice, v = double(j) / kLattice;
      const bool is_corner = quad ? (i == 0 || i == kLattice) && (j == 0 || j == kLattice)
                                  : (i == kLattice || j == kLattice || i + j == 0);
      double interpolated;
      Vec3 at;
      if (quad) {
        const double w[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
        at = c[0] * w[0] + c[1] * w[1] + c[2] * w[2] + c[3] * w[3];
        interpolated = corner[0] * w[0] + corner[1] * w[1] + corner[2] * w[2] + corner[3] * w[3];
      } else {
        const double w[3] = {1 - u - v, u, v};
        at = c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
        interpolated = corner[0] * w[0] + corner[1] * w[1] + corner[2] * w[2];
      }
      const double g = is_corner ? interpolated
                                 : Gain(element, Pulled(element, at), sources, surface_of, caster);
      worst = std::max(worst, std::abs(g - interpolated));
      sum += g;
      ++points;
    }
  }
  const double reference = radiosity.Sum() + sum / points;
  return reference > 0 ? worst / (tolerance * reference) : 0;
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
  if (!(ray_power > 0) || !(radiosity.Sum() > 0) || vertex_radiance.empty()) return 0;
  double mean = 0;
  for (const Rgb& v : vertex_radiance) mean += v.Sum();
  mean /= double(vertex_radiance.size());
  const double diff = std::abs(mean - radiosity.Sum());
  if (diff <= kNoiseSigmas * RayNoise(element, radiosity, ray_power)) return 0;
  return diff / (tolerance * radiosity.Sum());
}

}  // namespace radfarm
