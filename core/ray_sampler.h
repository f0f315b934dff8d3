// RaySampler: where ray k of a shooter starts and where it goes. Every sampler is a pure function
// of (seed, round, shooter, ray index), so any subset of a shot's rays can be generated anywhere.
//
// Each ray carries an integer weight. The form factor from shooter i to patch j is estimated as
// (sum of weights of i's rays that hit j) / (sum of weights of all of i's rays), so reductions are
// integer sums and exact in any order. Random and Sobol rays weigh 1; the seed paper's hemisphere
// grid weighs each direction by its cell's cosine-weighted solid angle, in fixed point.
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/sobol.h"
#include "core/solver_settings.h"
#include "core/vec3.h"

namespace radfarm {

struct RaySample {
  Vec3 origin;     // on the shooter's surface
  Vec3 direction;  // unit, into the shooter's front hemisphere
  uint64_t weight = 1;
};

// Up to kSize consecutive rays of one shot as structure of arrays, so the loops that make and trace
// them run over arrays the compiler vectorises. Coordinates as in RaySample.
struct RayBlock {
  static constexpr int kSize = 64;
  int count = 0;
  alignas(64) double origin_x[kSize], origin_y[kSize], origin_z[kSize];
  alignas(64) double direction_x[kSize], direction_y[kSize], direction_z[kSize];
  alignas(64) uint64_t weight[kSize];
};

class RaySampler;

// What sampling points on a patch needs beyond its corners, computed once per patch.
struct PatchSampling {
  double split = 1;   // TriangleSplit: share of the first triangle (0,1,2) in a quad's area
  double shrink = 0;  // RimShrink: how far points are pulled toward the centre, as a fraction
};

// The rays of one shot (one shooter in one round), with everything that does not depend on the ray
// index computed once: the shooter's frame, its triangle split and the shot's scramble. Cheap to
// copy; valid while the RaySampler and the patch it came from live.
class ShotSampler {
 public:
  RaySample Sample(uint64_t index) const;

  // Rays first, ..., first + count - 1 (count <= RayBlock::kSize): bit for bit the same as
  // Sample's, made a block at a time (the Sobol points incrementally, the arithmetic vectorised).
  void SampleBlock(uint64_t first, int count, RayBlock* block) const;

 private:
  friend class RaySampler;
  // Origins and directions of block->count rays from uniform numbers u[0..3] as Sample maps them.
  void MapUniforms(double* const u[4], RayBlock* block) const;

  ShotSampler(const RaySampler& sampler, const PatchShape& shooter, double rim_margin,
              uint64_t shot_key);

  const RaySampler& sampler_;
  const PatchShape& shooter_;
  Vec3 tangent_, bitangent_;
  PatchSampling sampling_;
  uint64_t shot_key_;
  ScrambledSobol4 sobol_;
};

class RaySampler {
 public:
  RaySampler(SamplerKind kind, uint64_t seed, double grid_step_degrees);

  SamplerKind kind() const { return kind_; }

  // Number of rays one shot of a shooter takes when the sampler fixes it (the grid), else 0: the
  // solver chooses the count from the shooter's unshot power.
  uint64_t FixedRaysPerShot() const;

  // The rays of `shooter` (a patch id) in `round`, starting at least `rim_margin` (a length: the
  // caster's origin_offset()) inside the patch's edges where the patch is large enough.
  ShotSampler Shot(const PatchShape& shooter, uint32_t shooter_id, uint32_t round,
                   double rim_margin) const;

  // Ray `index` of `shooter` in `round` (same as Shot(...).Sample(index)).
  RaySample Sample(const PatchShape& shooter, uint32_t shooter_id, uint32_t round,
                   double rim_margin, uint64_t index) const;

  // Sum of the weights of rays [0, count) of one shot: what a shooter's hit weights divide by.
  uint64_t TotalWeight(uint64_t count) const;

 private:
  friend class ShotSampler;
  RaySample GridSample(const PatchShape& shooter, const Vec3& t, const Vec3& b,
                       uint64_t index) const;

  SamplerKind kind_;
  uint64_t seed_;
  // Grid sampler tables: theta rows times phi columns, one fixed-point weight per row.
  uint32_t grid_theta_steps_ = 0;
  uint32_t grid_phi_steps_ = 0;
  std::vector<uint64_t> grid_row_weight_;
  uint64_t grid_total_weight_ = 0;
};

// Share of a quad's area in its first triangle (0,1,2); 1 for a triangle.
double TriangleSplit(const PatchShape& patch);

// How far SamplePatchPoint pulls points toward the patch's centre, as a fraction of the way: enough
// that points on the rim start `rim_margin` inside every edge, within [1e-5, 1e-2].
double RimShrink(const PatchShape& patch, double rim_margin);

PatchSampling PreparePatchSampling(const PatchShape& patch, double rim_margin);

// Maps two uniform numbers to a uniformly distributed point on the patch (a quad is picked as one
// of its two triangles in proportion to their areas), pulled toward the centre by sampling.shrink.
Vec3 SamplePatchPoint(const PatchShape& patch, const PatchSampling& sampling, double u, double v);

// Maps two uniform numbers to a cosine-weighted direction in the frame (t, b, n), n the normal.
Vec3 SampleCosineDirection(const Vec3& t, const Vec3& b, const Vec3& n, double u, double v);

}  // namespace radfarm
