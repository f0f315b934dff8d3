#include "core/ray_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

// Sampled points are pulled a hair toward the patch's centre: a ray starting within float
// resolution of the patch's rim could otherwise start behind a wall that meets the patch there and
// hit its back, or leave a closed room through the wall. The pull is a fraction of the way to the
// centre: at least kMinRimShrink, enough to move rim points `rim_margin` inside every edge, at most
// kMaxRimShrink (a tiny patch is sampled over 99% of its extent rather than at its centre).
constexpr double kMinRimShrink = 1e-5;
constexpr double kMaxRimShrink = 1e-2;

// cos and sin of 2 pi v for v in [0, 1), within 1e-10, by quadrant and Taylor polynomials to
// x^14 and x^15 on [0, pi/2): additions and multiplications only, so every build and every
// vector width rounds them alike (the C library's sinf/cosf come in FMA and non-FMA builds picked
// at load time, and vectorise only through libmvec, which rounds differently again). Inline: the
// one-ray path and the block loops share it.
inline void UnitCircle(double v, double* c, double* s) {
  const double q4 = 4 * v;
  // Quadrant 0..3 by comparisons, which vectorise where a conversion to int may not.
  const double quadrant = (q4 >= 1 ? 1.0 : 0.0) + (q4 >= 2 ? 1.0 : 0.0) + (q4 >= 3 ? 1.0 : 0.0);
  const double x = (q4 - quadrant) * (std::numbers::pi / 2);
  const double x2 = x * x;
  const double cx =
      1 +
      x2 * (-1.0 / 2 +
            x2 * (1.0 / 24 + x2 * (-1.0 / 720 +
                                   x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 +
                                                             x2 * (1.0 / 479001600 +
                                                                   x2 * (-1.0 / 87178291200)))))));
  const double sx =
      x * (1 + x2 * (-1.0 / 6 +
                     x2 * (1.0 / 120 +
                           x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 +
                                                     x2 * (-1.0 / 39916800 +
                                                           x2 * (1.0 / 6227020800 +
                                                                 x2 * (-1.0 / 1307674368000))))))));
  // Rotate by the quadrant: (cos, sin) of x + quadrant pi / 2.
  *c = quadrant == 0 ? cx : quadrant == 1 ? -sx : quadrant == 2 ? -cx : sx;
  *s = quadrant == 0 ? sx : quadrant == 1 ? cx : quadrant == 2 ? -sx : -cx;
}

// The block versions of SamplePatchPoint and SampleCosineDirection: the same operations in the same
// order on each ray (so the same bits), written as branch-free loops over arrays that GCC
// vectorises, in AVX-512 or AVX2 where the CPU has them (8 or 4 doubles a vector; add, multiply,
// divide and sqrt round alike at every width, and the file is built with -ffp-contract=off since
// contracting a*b+c into an FMA would change the bits). RADFARM_CLONES picks the width at load
// time; tests/core/ray_block_test.cc holds the width the machine picks to the one-ray path.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RADFARM_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define RADFARM_CLONES
#endif

// SampleTriangle's corner weights for n points of a quad split at `split` (or a triangle, split 1):
// which triangle each point falls in (u < split: the first), then 1 - sqrt(u'), sqrt(u') (1 - v)
// and sqrt(u') v for the point's u rescaled to its triangle.
RADFARM_CLONES void TriangleWeights(double split, const double* __restrict u,
                                    const double* __restrict v, int n, double* __restrict wa,
                                    double* __restrict wb, double* __restrict wc) {
  for (int i = 0; i < n; ++i) {
    const bool first = u[i] < split;
    const double uu = first ? u[i] / split : std::min((u[i] - split) / (1 - split), 1.0);
    const double su = std::sqrt(uu);
    wa[i] = 1 - su;
    wb[i] = su * (1 - v[i]);
    wc[i] = su * v[i];
  }
}

// One coordinate of SamplePatchPoint for n points from TriangleWeights: corner values a, b1/c1
// (first triangle) and b2/c2 (second), the centre's value `centre`.
RADFARM_CLONES void PatchPointCoordinate(double a, double b1, double c1, double b2, double c2,
                                         double centre, double split, double shrink,
                                         const double* __restrict u, const double* __restrict wa,
                                         const double* __restrict wb, const double* __restrict wc,
                                         int n, double* __restrict out) {
  for (int i = 0; i < n; ++i) {
    const bool first = u[i] < split;
    const double point = a * wa[i] + (first ? b1 : b2) * wb[i] + (first ? c1 : c2) * wc[i];
    out[i] = point + (centre - point) * shrink;
  }
}

// SampleCosineDirection for n rays.
RADFARM_CLONES void CosineDirections(Vec3 t, Vec3 b, Vec3 nrm, const double* __restrict u,
                                     const double* __restrict v, int n, double* __restrict dx,
                                     double* __restrict dy, double* __restrict dz) {
  for (int i = 0; i < n; ++i) {
    const double r = std::sqrt(u[i]);
    const double z = std::sqrt(std::max(0.0, 1 - u[i]));
    double c, s;
    UnitCircle(v[i], &c, &s);
    const double rc = r * c, rs = r * s;
    dx[i] = t.x * rc + b.x * rs + nrm.x * z;
    dy[i] = t.y * rc + b.y * rs + nrm.y * z;
    dz[i] = t.z * rc + b.z * rs + nrm.z * z;
  }
}

}  // namespace

double TriangleSplit(const PatchShape& patch) {
  if (patch.corner_count == 3) return 1;
  const auto& p = patch.corners;
  const double a0 = Length(Cross(p[1] - p[0], p[2] - p[0]));
  const double a1 = Length(Cross(p[2] - p[0], p[3] - p[0]));
  return a0 / (a0 + a1);
}

double RimShrink(const PatchShape& patch, double rim_margin) {
  // A rim point pulled a fraction f of the way to the centre moves f times the centre's distance
  // to the edge's line inside that edge, so the nearest edge line sets f.
  double inset = std::numeric_limits<double>::infinity();
  for (uint32_t i = 0; i < patch.corner_count; ++i) {
    const Vec3& a = patch.corners[i];
    const Vec3 edge = patch.corners[(i + 1) % patch.corner_count] - a;
    const double length = Length(edge);
    if (length > 0) inset = std::min(inset, Length(Cross(patch.centre - a, edge)) / length);
  }
  if (!(inset > 0) || !(rim_margin > 0)) return kMinRimShrink;
  return std::clamp(rim_margin / inset, kMinRimShrink, kMaxRimShrink);
}

PatchSampling PreparePatchSampling(const PatchShape& patch, double rim_margin) {
  return {TriangleSplit(patch), RimShrink(patch, rim_margin)};
}

Vec3 SamplePatchPoint(const PatchShape& patch, const PatchSampling& sampling, double u, double v) {
  const auto& p = patch.corners;
  const double split = sampling.split;
  const Vec3 point =
      u < split ? SampleTriangle(p[0], p[1], p[2], u / split, v)
                : SampleTriangle(p[0], p[2], p[3], std::min((u - split) / (1 - split), 1.0), v);
  return point + (patch.centre - point) * sampling.shrink;
}

Vec3 SampleCosineDirection(const Vec3& t, const Vec3& b, const Vec3& n, double u, double v) {
  const double r = std::sqrt(u);
  const double z = std::sqrt(std::max(0.0, 1 - u));
  double c, s;
  UnitCircle(v, &c, &s);
  return t * (r * c) + b * (r * s) + n * z;
}

ShotSampler::ShotSampler(const RaySampler& sampler, const PatchShape& shooter, double rim_margin,
                         uint64_t shot_key)
    : sampler_(sampler),
      shooter_(shooter),
      sampling_(PreparePatchSampling(shooter, rim_margin)),
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
      return {SamplePatchPoint(shooter_, sampling_, rng.Uniform(0), rng.Uniform(1)),
              SampleCosineDirection(tangent_, bitangent_, shooter_.normal, rng.Uniform(2),
                                    rng.Uniform(3)),
              1};
    }
    case SamplerKind::kSobol: {
      const auto u = sobol_.Point(static_cast<uint32_t>(index));
      return {SamplePatchPoint(shooter_, sampling_, u[0], u[1]),
              SampleCosineDirection(tangent_, bitangent_, shooter_.normal, u[2], u[3]), 1};
    }
  }
  return {};
}

void ShotSampler::SampleBlock(uint64_t first, int count, RayBlock* block) const {
  block->count = count;
  if (sampler_.kind_ == SamplerKind::kGrid) {
    for (int i = 0; i < count; ++i) {
      const RaySample ray = sampler_.GridSample(shooter_, tangent_, bitangent_, first + i);
      block->origin_x[i] = ray.origin.x;
      block->origin_y[i] = ray.origin.y;
      block->origin_z[i] = ray.origin.z;
      block->direction_x[i] = ray.direction.x;
      block->direction_y[i] = ray.direction.y;
      block->direction_z[i] = ray.direction.z;
      block->weight[i] = ray.weight;
    }
    return;
  }
  alignas(64) double uniforms[4][RayBlock::kSize];
  double* const u[4] = {uniforms[0], uniforms[1], uniforms[2], uniforms[3]};
  if (sampler_.kind_ == SamplerKind::kSobol) {
    sobol_.Points(static_cast<uint32_t>(first), count, u);
  } else {
    for (int i = 0; i < count; ++i) {
      const CounterRng rng(HashWords(shot_key_, first + i));
      for (uint32_t d = 0; d < 4; ++d) u[d][i] = rng.Uniform(d);
    }
  }
  for (int i = 0; i < count; ++i) block->weight[i] = 1;
  MapUniforms(u, block);
}

void ShotSampler::MapUniforms(double* const u[4], RayBlock* block) const {
  const int n = block->count;
  const auto& p = shooter_.corners;
  const Vec3& c = shooter_.centre;
  const double split = sampling_.split, shrink = sampling_.shrink;
  alignas(64) double wa[RayBlock::kSize], wb[RayBlock::kSize], wc[RayBlock::kSize];
  TriangleWeights(split, u[0], u[1], n, wa, wb, wc);
  PatchPointCoordinate(p[0].x, p[1].x, p[2].x, p[2].x, p[3].x, c.x, split, shrink, u[0], wa, wb, wc,
                       n, block->origin_x);
  PatchPointCoordinate(p[0].y, p[1].y, p[2].y, p[2].y, p[3].y, c.y, split, shrink, u[0], wa, wb, wc,
                       n, block->origin_y);
  PatchPointCoordinate(p[0].z, p[1].z, p[2].z, p[2].z, p[3].z, c.z, split, shrink, u[0], wa, wb, wc,
                       n, block->origin_z);
  CosineDirections(tangent_, bitangent_, shooter_.normal, u[2], u[3], n, block->direction_x,
                   block->direction_y, block->direction_z);
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

RaySample RaySampler::GridSample(const PatchShape& shooter, const Vec3& t, const Vec3& b,
                                 uint64_t index) const {
  const uint32_t row = static_cast<uint32_t>(index / grid_phi_steps_);
  const uint32_t col = static_cast<uint32_t>(index % grid_phi_steps_);
  const double theta = (row + 0.5) * (std::numbers::pi / 2 / grid_theta_steps_);
  const double phi = (col + 0.5) * (2 * std::numbers::pi / grid_phi_steps_);
  const Vec3 dir = t * (std::sin(theta) * std::cos(phi)) + b * (std::sin(theta) * std::sin(phi)) +
                   shooter.normal * std::cos(theta);
  return {shooter.centre, dir, grid_row_weight_[row]};
}

ShotSampler RaySampler::Shot(const PatchShape& shooter, uint32_t shooter_id, uint32_t round,
                             double rim_margin) const {
  return ShotSampler(*this, shooter, rim_margin, ShotKey(seed_, round, shooter_id));
}

RaySample RaySampler::Sample(const PatchShape& shooter, uint32_t shooter_id, uint32_t round,
                             double rim_margin, uint64_t index) const {
  return Shot(shooter, shooter_id, round, rim_margin).Sample(index);
}

}  // namespace radfarm
