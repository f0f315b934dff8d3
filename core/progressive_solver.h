// ProgressiveSolver: the state of a progressive-refinement (Southwell) radiosity solution and the
// two deterministic steps of a round. It does no ray casting itself: PlanRound() says which rays to
// cast (as batches), and ApplyRound() folds their integer hit counts into the solution. The round
// driver (solve/round_driver.h) drives it for `radfarm render` and the farm's master alike, so
// they produce bit-identical results.
//
// Units: radiosity is kept in the units of emitted radiance (MTL Ke), i.e. B/pi. The radiosity
// equation is linear, so the factor pi cancels everywhere and the CSV can print B directly.
// "Power" of patch i is A_i times a radiance, summed over the three channels.
//
// Over-relaxation (settings.overrelaxation = omega; Gortler, Cohen & Slusallek 1993; Feda &
// Purgathofer 1992): a shooter with unshot radiosity r shoots omega * r and keeps (1 - omega) * r,
// so its displayed radiosity (which includes its unshot) is unchanged and receivers gain omega
// times the plain Southwell amount. Above 1 the kept unshot is negative and is later shot as
// negative light, so shooters are ranked, given rays and counted for convergence by the magnitude
// of their unshot power, A_i * (|r| + |g| + |b|). omega = 1 is plain Southwell, to the bit.
//
// Final gather (settings.gather_rays > 0, GatherOn): the solver starts from the direct light of
// every patch, computed from the patch (PatchDirectLight: exact where no shadow falls), so the
// emitters never shoot; their light is delivered, its reflected part is the first unshot. (Unless
// the scene has so many emitter patches that this would cost more shadow rays than the gather
// casts: then the emitters shoot, and the gather takes their light with the rest.) When
// the unshot fraction is at or below the tolerance, PlanRound plans one gather round instead of a
// shooting round: every reflecting patch not facing the void (core/gathering_patches.h) casts
// gather_rays rays (ordinary batches, so the farm
// runs them like any other), and ApplyRound reads each patch's hit weights the other way round:
// the mean radiosity, less emission, of what its rays hit is the light that bounced onto it. Its
// radiosity becomes E + rho * (direct + that), and every unshot is zero: the solve is done (the
// unshot left was below the tolerance; the gather carries it one more bounce). Shooting noise on
// a patch is that of the hits it received, so small patches are noisy; gathering noise is that of
// its own gather rays, the same for every patch, and averages the shooting noise of the patches it
// sees. A resumed solve needs no flag: a gather is pending exactly while some unshot is not zero.
//
// Round lifecycle:  PlanRound() -> [batches computed anywhere, any order] -> ApplyRound().
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/batch.h"
#include "core/direct_start.h"
#include "core/patch_scene.h"
#include "core/ray_sampler.h"
#include "core/rgb.h"
#include "core/solver_settings.h"

namespace radfarm {

struct Shot {
  uint32_t shooter = 0;  // patch id
  uint64_t rays = 0;
};

struct RoundPlan {
  uint32_t round = 0;
  std::vector<Shot> shots;     // increasing patch id
  std::vector<Batch> batches;  // every shot cut into batches, in shot order
  uint64_t rays = 0;
  bool capped = false;  // trimmed to a ray cap: the last round of a ray budget
  bool gather = false;  // the final gather round: shooters are gathering patches, no power moves
};

// Energy bookkeeping (channel sums). At every round boundary
//   emitted == absorbed + signed unshot + escaped   (to rounding)
// because each shot's power is divided exactly among its rays' fates and taken exactly from its
// shooter's unshot (ProgressiveSolver::SignedUnshotPower()). `unshot` is the sum of the
// magnitudes instead, the convergence measure; the two differ only when over-relaxation has left
// some unshot negative.
struct EnergyAccount {
  double emitted = 0;
  double absorbed = 0;
  double escaped = 0;
  double unshot = 0;  // sum over patches of A_i * (|r| + |g| + |b|) of the unshot radiosity
};

// A gather cut by a budget gets at least gather_rays / kMinGatherShare rays per patch, or none:
// its error goes as 1 / sqrt(rays), so a gather of a ray or two a patch is far noisier than the
// rounds alone (docs/SOLVER.md).
inline constexpr uint32_t kMinGatherShare = 16;

class ProgressiveSolver {
 public:
  // `start`, if given, traces the direct light the solve starts from (core/direct_start.h);
  // without, it is traced here.
  ProgressiveSolver(const PatchScene& scene, const SolverSettings& settings,
                    const StartLightSource& start = {});

  // With the final gather on (GatherOn(settings)), computes the direct light first (ray casting
  // on `settings.threads` threads: this is the one place the solver casts rays itself).
  //
  // Plans the next round from the current unshot radiosity: the gather round when a gather is
  // pending and the unshot fraction is at or below the tolerance (cut to `ray_cap` if set and
  // smaller, and marked capped; empty if that is less than a ray per patch: the solve then ends
  // ungathered). Empty when nothing is left to shoot.
  // With ray_cap > 0 the round casts at most that many rays (every proportional shot keeps at least
  // one ray, and with fewer rays than shooters only the strongest shoot, one ray each; the grid
  // drops its weakest shots, keeping at least one) and is marked capped.
  RoundPlan PlanRound(uint32_t batch_rays, uint64_t ray_cap = 0) const;

  // The shooting round PlanRound would plan next without a cap, as totals: its rays and the
  // power it shoots over the emitted power. Zeros where the next round is the gather, nothing is
  // left to shoot, or shots have a fixed size (the grid sampler).
  struct RoundSize {
    uint64_t rays = 0;
    double power = 0;
  };
  RoundSize NextShootingRound() const;
  // The share of a shot's power that comes back as unshot, estimated for pacing a budget
  // (core/solve_control.h PacedRoundCap): the patches' area-weighted mean reflectance, less the
  // rays that escaped so far (from the energy account), in [0, 0.95].
  double EstimatedCarry() const;

  // Folds the round's results into the solution. `results[k]` is the result of plan.batches[k].
  void ApplyRound(const RoundPlan& plan, const std::vector<BatchResult>& results);

  // ApplyRound in steps, for folding shots in as their batches arrive (core/round_reduction.h):
  // BeginRound, ApplyShot for every shot in increasing shot order (`results`: that shot's
  // batches, in any order), EndRound. The same arithmetic in the same order as ApplyRound, so the
  // same bits; nothing else may be called on the solver in between.
  void BeginRound(const RoundPlan& plan);
  void ApplyShot(const RoundPlan& plan, size_t shot, std::span<const BatchResult> results);
  void EndRound(const RoundPlan& plan);

  const std::vector<Rgb>& radiosity() const { return radiosity_; }
  const std::vector<Rgb>& unshot() const { return unshot_; }
  const EnergyAccount& energy() const { return energy_; }
  // True while the final gather is on and has not run: some unshot radiosity is not zero.
  bool GatherPending() const;
  // The next round PlanRound plans is the gather: one is pending and the unshot fraction is at or
  // below the tolerance.
  bool GatherNext() const { return GatherPending() && UnshotFraction() <= settings_.tolerance; }
  // Patches a gather round gathers for: those that reflect and do not face the void
  // (core/gathering_patches.h).
  uint64_t GatheringPatches() const;
  // The fewest rays a gather cut by a budget is planned with: kMinGatherShare of gather_rays per
  // gathering patch (at least one). With fewer, each patch's gathered light would be noisier
  // than the shooting's estimate it replaces, so the solve stops before it instead.
  uint64_t MinGatherRays() const;
  // The rays the final gather will cast (before any ray budget cuts it): 0 when none is pending.
  uint64_t PendingGatherRays() const;
  // The gather round PlanRound will plan when the gather comes (uncut by a ray budget), planned
  // now: its batches depend on the scene and settings alone (core/batch.h: keyed by
  // kGatherRound), so they can be traced before the shooting rounds end. Empty when no gather is
  // pending.
  RoundPlan PlanPendingGather(uint32_t batch_rays) const;
  // The direct light of every patch the solve started from: the punctual lights' (always), and
  // the emitter patches' where EmittersInDirectStart (else they shoot as usual). Empty when
  // neither is in it.
  const std::vector<Rgb>& direct_light() const { return direct_; }
  // The shadow rays the direct light above cast: they count against the ray budget
  // (core/solve_control.h), and are the same whatever the threads.
  uint64_t start_rays() const { return start_rays_; }
  // What the punctual lamps delivered in the start, counted as emitted power.
  double punctual_power() const { return punctual_power_; }
  // Unshot power (magnitudes) over emitted power: the convergence measure.
  double UnshotFraction() const;
  // Sum over patches of A_i times the unshot radiosity's channel sum, with its sign: the term of
  // the energy account. Computed from the state on each call.
  double SignedUnshotPower() const;
  uint32_t rounds_done() const { return rounds_done_; }
  const RaySampler& sampler() const { return sampler_; }

  // Replaces the state, e.g. when resuming from a checkpoint; sizes must match the scene.
  // energy.unshot is not taken but recomputed from `unshot`, as ApplyRound computes it.
  void Restore(uint32_t rounds_done, std::vector<Rgb> radiosity, std::vector<Rgb> unshot,
               const EnergyAccount& energy);
  // A re-bake's start (core/warm_start.h), before round 0: the state becomes `radiosity` and the
  // signed `unshot`, and no final gather follows. The previous solution's bounced light was
  // gathered already; what is left to shoot is a change, small beside it, whose noise a gather of
  // every patch would cost more to remove than it is worth. The energy account keeps what the
  // start emitted and saw escape and books the rest as absorbed, so it balances.
  void StartFrom(std::vector<Rgb> radiosity, std::vector<Rgb> unshot);
  // Whether the emitter patches' light is in the direct start (they then never shoot).
  bool emitters_direct() const { return emitters_direct_; }

 private:
  // A_i * (|r| + |g| + |b|) of the unshot radiosity.
  double UnshotPower(uint32_t patch) const;
  double TotalUnshotPower() const;
  RoundPlan PlanGather(uint32_t batch_rays, uint64_t ray_cap) const;
  // The next shooting round's shots at their full rays, and the power they shoot (fraction of the
  // emitted power). With `ray_cap`, only as many shooters as it gives a shot each (the grid's
  // fixed shots) or a ray each (fewer rays than shooters), the strongest, and `capped` set.
  std::vector<Shot> PlanShots(uint64_t ray_cap, double* power, bool* capped) const;

  const PatchScene& scene_;
  SolverSettings settings_;  // shot_rays resolved (never 0)
  RaySampler sampler_;
  std::vector<Rgb> radiosity_;
  std::vector<Rgb> unshot_;
  bool gather_ = false;          // GatherOn(settings)
  std::vector<bool> gathering_;  // by patch: GatheringPatchMask
  std::vector<Rgb> direct_;      // per patch, Ke units; empty unless the solve started from it
  // The emitter patches' light is in direct_ (EmittersInDirectStart): they do not shoot, and the
  // gather takes only bounced light. Otherwise direct_ holds the punctual lights' alone, if any.
  bool emitters_direct_ = false;
  uint64_t start_rays_ = 0;
  double punctual_power_ = 0;
  double mean_reflectance_ = 0;  // area-weighted, channel mean (EstimatedCarry)
  EnergyAccount energy_;
  uint32_t rounds_done_ = 0;
  // Within a round (BeginRound to EndRound): hit weights per patch, zero between shots, and per
  // shot the power it shoots (shooting) or the light it gathered (gather).
  std::vector<uint64_t> hit_weight_;
  std::vector<Rgb> shot_light_;
};

}  // namespace radfarm
