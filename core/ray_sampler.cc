#include "core/ray_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/counter_rng.h"
#include "core/sobol.h"

namespace radfarm {
namespace {

// Fixed-point scale of grid weights: 2^40 per unit of cosine-weighted solid angle / pi keeps
// 12 significant digits per ray and leaves the 64-bit sums far from overflow.
constexpr double kGridWeightScale = 0x1.0p40;

// Keys the scramble or random stream of one shot.
uint64_t ShotKey(uint64_t seed, uint32_t round, uint32_t shooter) {
  return HashWords(seed, round, shooter);
}

Vec3 SampleTriangle(const Vec3& a, const Vec3& b, const Vec3& c, double u, double v) {
  const double su = std::sqrt(u);
  return a * (1 - su) + b * (su * (1 - v)) + c * (su * v);
}

}  // namespace

double TriangleSplit(const Patch& patch) {
  if (patch.corner_count == 3) return 1;
  const auto& p = patch.corners;
  const double a0 = Length(Cross(p[1] - p[0], p[2] - p[0]));
  const double a1 = Length(Cross(p[2] - p[0], p[3] - p[0]));
  return a0 / (a0 + a1);
}

Vec3 SamplePatchPoint(const Patch& patch, double split, double u, double v) {
  const auto& p = patch.corners;
  const Vec3 point =
      u < split ? SampleTriangle(p[0], p[1], p[2], u / split, v)
                : SampleTriangle(p[0], p[2], p[3], std::min((u - split) / (1 - split), 1.0), v);
  // Pull the point a hair toward the centre: a ray starting within a float ulp of the patch's rim
  // could otherwise start behind a wall that meets the patch there and hit its back.
  constexpr double kRimShrink = 1e-5;
  return point + (patch.centre - point) * kRimShrink;
}

Vec3 SampleCosineDirection(const Vec3& t, const Vec3& b, const Vec3& n, double u, double v) {
  const double r = std::sqrt(u);
  // Single-precision trigonometry: twice as fast, and Embree traces in single precision anyway.
  const float phi = static_cast<float>(2 * std::numbers::pi * v);
  const double z = std::sqrt(std::max(0.0, 1 - u));
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * z;
}

ShotSampler::ShotSampler(const RaySampler& sampler, const Patch& shooter, uint64_t shot_key)
    : sampler_(sampler),
      shooter_(shooter),
      triangle_split_(TriangleSplit(shooter)),
      shot_key_(shot_key),
      sobol_(shot_key) {
  OrthonormalBasis(shooter.normal, &tangent_, &bitangent_);
}

RaySample ShotSampler::Sample(uint64_t index) const {
  switch (sampler_.kind_) {
    case SamplerKind::kGrid:
      return sampler_.GridSample(shooter_, tangent_, bitangent_, index);
    case SamplerKind::kRandom: {
      const CounterRng rng(HashWords(shot_key_, index));
      return {SamplePatchPoint(shooter_, triangle_split_, rng.Uniform(0), rng.Uniform(1)),
              SampleCosineDirection(tangent_, bitangent_, shooter_.normal, rng.Uniform(2),
                                    rng.Uniform(3)),
              1};
    }
    case SamplerKind::kSobol: {
      const auto u = sobol_.Point(static_cast<uint32_t>(index));
      return {SamplePatchPoint(shooter_, triangle_split_, u[0], u[1]),
              SampleCosineDirection(tangent_, bitangent_, shooter_.normal, u[2], u[3]), 1};
    }
  }
  return {};
}

RaySampler::RaySampler(SamplerKind kind, uint64_t seed, double grid_step_degrees)
    : kind_(kind), seed_(seed) {
  if (kind_ != SamplerKind::kGrid) return;
  // Cells of the seed's grid: theta in [0, 90) and phi in [0, 360) in steps of the given angle.
  grid_theta_steps_ = std::max(1u, static_cast<uint32_t>(std::lround(90.0 / grid_step_degrees)));
  grid_phi_steps_ = std::max(1u, static_cast<uint32_t>(std::lround(360.0 / grid_step_degrees)));
  const double dtheta = std::numbers::pi / 2 / grid_theta_steps_;
  const double dphi = 2 * std::numbers::pi / grid_phi_steps_;
  for (uint32_t i = 0; i < grid_theta_steps_; ++i) {
    // Exact cosine-weighted solid angle of the cell over pi: (sin^2 t1 - sin^2 t0) / 2 * dphi / pi.
    const double s0 = std::sin(i * dtheta), s1 = std::sin((i + 1) * dtheta);
    const double w = (s1 * s1 - s0 * s0) / 2 * dphi / std::numbers::pi;
    grid_row_weight_.push_back(static_cast<uint64_t>(std::llround(w * kGridWeightScale)));
    grid_total_weight_ += grid_row_weight_.back() * grid_phi_steps_;
  }
}

uint64_t RaySampler::FixedRaysPerShot() const {
  return kind_ == SamplerKind::kGrid ? uint64_t{grid_theta_steps_} * grid_phi_steps_ : 0;
}

uint64_t RaySampler::TotalWeight(uint64_t count) const {
  if (kind_ != SamplerKind::kGrid) return count;
  // Only whole shots are used with the grid; a partial shot sums its rows.
  if (count == FixedRaysPerShot()) return grid_total_weight_;
  uint64_t total = 0;
  for (uint64_t k = 0; k < count; ++k) total += grid_row_weight_[k / grid_phi_steps_];
  return total;
}

RaySample RaySampler::GridSample(const Patch& shooter, const Vec3& t, const Vec3& b,
                                 uint64_t index) const {
  const uint32_t row = static_cast<uint32_t>(index / grid_phi_steps_);
  const uint32_t col = static_cast<uint32_t>(index % grid_phi_steps_);
  const double theta = (row + 0.5) * (std::numbers::pi / 2 / grid_theta_steps_);
  const double phi = (col + 0.5) * (2 * std::numbers::pi / grid_phi_steps_);
  const Vec3 dir = t * (std::sin(theta) * std::cos(phi)) + b * (std::sin(theta) * std::sin(phi)) +
                   shooter.normal * std::cos(theta);
  return {shooter.centre, dir, grid_row_weight_[row]};
}

ShotSampler RaySampler::Shot(const Patch& shooter, uint32_t shooter_id, uint32_t round) const {
  return ShotSampler(*this, shooter, ShotKey(seed_, round, shooter_id));
}

RaySample RaySampler::Sample(const Patch& shooter, uint32_t shooter_id, uint32_t round,
                             uint64_t index) const {
  return Shot(shooter, shooter_id, round).Sample(index);
}

}  // namespace radfarm
