#include "core/progressive_solver.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <span>

#include "core/direct_light.h"
#include "core/gathering_patches.h"

namespace radfarm {
namespace {

// Sobol indices are 32-bit; a single shot never needs more rays than this.
constexpr uint64_t kMaxRaysPerShot = uint64_t{1} << 31;

// One shot's batches summed: hit weights per patch (integers: exact in any order), and the patches
// hit in increasing order, the order their light is then applied in.
struct ShotHits {
  std::vector<uint32_t> touched;
  uint64_t escaped = 0, back = 0;
};

// Sums one shot's batch results into `hit_weight` (zero where not touched).
ShotHits SumShotHits(std::span<const BatchResult> results, std::vector<uint64_t>* hit_weight) {
  ShotHits out;
  std::vector<uint64_t>& weight = *hit_weight;
  for (const BatchResult& r : results) {
    out.escaped += r.escaped_weight;
    out.back += r.back_weight;
    for (const PatchHits& h : r.hits) {
      if (weight[h.patch] == 0) out.touched.push_back(h.patch);
      weight[h.patch] += h.weight;
    }
  }
  std::sort(out.touched.begin(), out.touched.end());
  return out;
}

}  // namespace

ProgressiveSolver::ProgressiveSolver(const PatchScene& scene, const SolverSettings& settings,
                                     const StartLightSource& start)
    : scene_(scene),
      settings_(settings),
      sampler_(settings.sampler, settings.seed, settings.grid_step_degrees),
      radiosity_(scene.patches.size()),
      unshot_(scene.patches.size()) {
  settings_.shot_rays = ResolvedShotRays(settings_, scene.patches.size());
  double area = 0;
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    radiosity_[i] = p.emission;
    unshot_[i] = p.emission;
    energy_.emitted += p.area * p.emission.Sum();
    area += p.area;
    mean_reflectance_ += p.area * p.reflectance.Sum() / 3;
  }
  if (area > 0) mean_reflectance_ /= area;
  energy_.unshot = energy_.emitted;
  gather_ = GatherOn(settings_);
  gathering_ = GatheringPatchMask(scene);
  // Start from the direct light where DirectLightSections says it pays. Elsewhere (a furnace, a
  // sky of emitters) the emitters shoot as usual and the gather sees their light like any other.
  // The direct light is delivered (absorbed or reflected), the reflected part is unshot, and what
  // the emitters emitted beyond it left the scene or met a back face. Punctual lights are always
  // in the start (they have no surface to shoot from); what they deliver counts as their emitted
  // power (a sun's whole power has no bound).
  double punctual_power = 0;
  if (!start) {
    direct_ = StartingDirectLight(scene, settings_, &punctual_power, &start_rays_);
  } else if (const std::optional<StartWork> work = StartWorkOf(scene, settings_)) {
    StartLight light = start(scene, *work);
    direct_ = std::move(light.direct);
    punctual_power = light.punctual_power;
    start_rays_ = light.shadow_rays;
  }
  if (direct_.empty()) return;
  emitters_direct_ = EmittersInDirectStart(scene, settings_);
  const double emitter_power = energy_.emitted;
  punctual_power_ = punctual_power;
  energy_.emitted += punctual_power;
  double delivered = 0;
  energy_.absorbed = 0;
  for (size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    const Rgb reflected = p.reflectance * direct_[i];
    radiosity_[i] = p.emission + reflected;
    unshot_[i] = emitters_direct_ ? reflected : p.emission + reflected;
    delivered += p.area * direct_[i].Sum();
    energy_.absorbed += p.area * (direct_[i] - reflected).Sum();
  }
  energy_.escaped = energy_.emitted - delivered - (emitters_direct_ ? 0.0 : emitter_power);
  energy_.unshot = TotalUnshotPower();
}

bool ProgressiveSolver::GatherPending() const {
  if (!gather_) return false;
  for (const Rgb& u : unshot_) {
    if (!(u == Rgb{})) return true;
  }
  return false;
}

double ProgressiveSolver::UnshotPower(uint32_t patch) const {
  return scene_.patches[patch].area * unshot_[patch].AbsSum();
}

double ProgressiveSolver::TotalUnshotPower() const {
  double unshot = 0;
  for (uint32_t i = 0; i < scene_.patches.size(); ++i) unshot += UnshotPower(i);
  return unshot;
}

double ProgressiveSolver::SignedUnshotPower() const {
  double unshot = 0;
  for (uint32_t i = 0; i < scene_.patches.size(); ++i) {
    unshot += scene_.patches[i].area * unshot_[i].Sum();
  }
  return unshot;
}

double ProgressiveSolver::UnshotFraction() const {
  return energy_.emitted > 0 ? energy_.unshot / energy_.emitted : 0.0;
}

namespace {

// Keeps the `limit` shooters with the most unshot power (ties broken by patch id, so the choice is
// total), in patch order.
void KeepStrongest(size_t limit, const std::function<double(uint32_t)>& power,
                   std::vector<uint32_t>* shooters) {
  if (limit == 0 || shooters->size() <= limit) return;
  std::nth_element(shooters->begin(), shooters->begin() + (limit - 1), shooters->end(),
                   [&](uint32_t a, uint32_t b) {
                     const double pa = power(a), pb = power(b);
                     return pa != pb ? pa > pb : a < b;
                   });
  shooters->resize(limit);
  std::sort(shooters->begin(), shooters->end());
}

}  // namespace

uint64_t ProgressiveSolver::GatheringPatches() const {
  uint64_t n = 0;
  for (bool gathers : gathering_) n += gathers;
  return n;
}

uint64_t ProgressiveSolver::MinGatherRays() const {
  return GatheringPatches() * std::max<uint64_t>(1, settings_.gather_rays / kMinGatherShare);
}

uint64_t ProgressiveSolver::PendingGatherRays() const {
  return GatherPending() ? GatheringPatches() * settings_.gather_rays : 0;
}

RoundPlan ProgressiveSolver::PlanPendingGather(uint32_t batch_rays) const {
  return GatherPending() ? PlanGather(batch_rays, 0) : RoundPlan{};
}

RoundPlan ProgressiveSolver::PlanGather(uint32_t batch_rays, uint64_t ray_cap) const {
  RoundPlan plan;
  plan.round = rounds_done_;
  plan.gather = true;
  for (uint32_t i = 0; i < scene_.patches.size(); ++i) {
    if (!gathering_[i]) continue;  // core/gathering_patches.h
    plan.shots.push_back({i, settings_.gather_rays});
    plan.rays += settings_.gather_rays;
  }
  if (ray_cap > 0 && plan.rays > ray_cap) {
    // The last round of a ray budget: the budget's rays spread evenly over the gathering patches
    // (the first ones one more), unless it cannot give each its share (MinGatherRays).
    const uint64_t patches = plan.shots.size();
    if (ray_cap < MinGatherRays()) return RoundPlan{};
    for (size_t s = 0; s < patches; ++s)
      plan.shots[s].rays = ray_cap / patches + (s < ray_cap % patches);
    plan.rays = ray_cap;
    plan.capped = true;
  }
  for (const Shot& shot : plan.shots) {
    AppendShotBatches(kGatherRound, shot.shooter, shot.rays, batch_rays, &plan.batches);
  }
  return plan;
}

std::vector<Shot> ProgressiveSolver::PlanShots(uint64_t ray_cap, double* power_shot,
                                               bool* capped) const {
  const auto power = [this](uint32_t patch) { return UnshotPower(patch); };
  std::vector<uint32_t> candidates;
  for (uint32_t i = 0; i < scene_.patches.size(); ++i) {
    if (UnshotPower(i) > 0) candidates.push_back(i);
  }
  KeepStrongest(settings_.shooters_per_round, power, &candidates);

  const uint64_t fixed = sampler_.FixedRaysPerShot();
  if (fixed > 0 && ray_cap > 0 && candidates.size() * fixed > ray_cap) {
    // A fixed-size shot cannot be cut: shoot from fewer patches (at least one).
    KeepStrongest(std::max<uint64_t>(1, ray_cap / fixed), power, &candidates);
    *capped = true;
  }
  if (fixed == 0 && ray_cap > 0 && candidates.size() > ray_cap) {
    // Fewer rays left than shooters (a paced budget's last round): a ray each from the strongest,
    // so the round casts the rays left and no more.
    KeepStrongest(ray_cap, power, &candidates);
    *capped = true;
  }
  std::vector<Shot> shots;
  shots.reserve(candidates.size());
  *power_shot = 0;
  for (uint32_t shooter : candidates) {
    uint64_t rays = fixed;
    const double share = settings_.overrelaxation * UnshotPower(shooter) / energy_.emitted;
    *power_shot += share;
    if (rays == 0) {
      // Rays in proportion to the power shot (omega times the unshot), so every unit of power is
      // carried by the same number of rays whichever round it is shot in and whatever omega.
      const double wanted = std::ceil(double(settings_.shot_rays) * share);
      rays = std::clamp<uint64_t>(static_cast<uint64_t>(std::min(wanted, 1e18)),
                                  settings_.min_shooter_rays, kMaxRaysPerShot);
    }
    shots.push_back({shooter, rays});
  }
  return shots;
}

ProgressiveSolver::RoundSize ProgressiveSolver::NextShootingRound() const {
  if (GatherNext() || sampler_.FixedRaysPerShot() > 0) return {};
  RoundSize size;
  bool capped = false;
  for (const Shot& shot : PlanShots(0, &size.power, &capped)) size.rays += shot.rays;
  return size;
}

double ProgressiveSolver::EstimatedCarry() const {
  // A shot's rays escape (share e), or land and reflect rho of their power. The account holds
  // escaped = e S and absorbed = (1 - rho)(1 - e) S for the power S shot so far (and the direct
  // start's light, absorbed where it landed). An estimate, a little under the carry measured round
  // to round. Too low, and the last paced round is trimmed to what is left; too high, and the
  // solve converges with some of the budget unspent.
  const double rho = mean_reflectance_;
  double escape = 0;
  if (energy_.escaped > 0) {
    escape = (1 - rho) * energy_.escaped / (energy_.absorbed + (1 - rho) * energy_.escaped);
  }
  return std::clamp(rho * (1 - escape), 0.0, 0.95);
}

RoundPlan ProgressiveSolver::PlanRound(uint32_t batch_rays, uint64_t ray_cap) const {
  if (GatherNext()) {
    return PlanGather(batch_rays, ray_cap);
  }
  RoundPlan plan;
  plan.round = rounds_done_;
  double power = 0;
  plan.shots = PlanShots(ray_cap, &power, &plan.capped);
  for (const Shot& shot : plan.shots) plan.rays += shot.rays;
  const uint64_t fixed = sampler_.FixedRaysPerShot();
  if (fixed == 0 && ray_cap > 0 && plan.rays > ray_cap) {
    // The last round of a ray budget: fewer rays for every shot, in proportion (at least one each).
    const double scale = double(ray_cap) / double(plan.rays);
    plan.rays = 0;
    for (Shot& shot : plan.shots) {
      shot.rays = std::max<uint64_t>(1, static_cast<uint64_t>(double(shot.rays) * scale));
      plan.rays += shot.rays;
    }
    // Rounding down left less than one ray per shot unspent: one more each, in shot order, until
    // the budget is spent exactly (a job with a ray budget then casts exactly that many rays).
    for (size_t s = 0; s < plan.shots.size() && plan.rays < ray_cap; ++s) {
      if (plan.shots[s].rays < kMaxRaysPerShot) {
        ++plan.shots[s].rays;
        ++plan.rays;
      }
    }
    // Or the ray each shot keeps made it more: taken back from the last shots that have more.
    for (size_t s = plan.shots.size(); s-- > 0 && plan.rays > ray_cap;) {
      const uint64_t back = std::min(plan.shots[s].rays - 1, plan.rays - ray_cap);
      plan.shots[s].rays -= back;
      plan.rays -= back;
    }
    plan.capped = true;
  }
  for (const Shot& shot : plan.shots) {
    AppendShotBatches(plan.round, shot.shooter, shot.rays, batch_rays, &plan.batches);
  }
  return plan;
}

void ProgressiveSolver::ApplyRound(const RoundPlan& plan, const std::vector<BatchResult>& results) {
  BeginRound(plan);
  size_t b = 0;
  for (size_t s = 0; s < plan.shots.size(); ++s) {
    const size_t first = b;
    while (b < plan.batches.size() && plan.batches[b].shooter == plan.shots[s].shooter) ++b;
    ApplyShot(plan, s, std::span(results).subspan(first, b - first));
  }
  EndRound(plan);
}

void ProgressiveSolver::BeginRound(const RoundPlan& plan) {
  hit_weight_.assign(scene_.patches.size(), 0);
  shot_light_.assign(plan.shots.size(), Rgb{});
  if (plan.gather) return;
  // Take every shooter's unshot radiosity first: shots of one round all start from the state at
  // the start of the round (a shooter may also receive light in its own round). Relaxing by omega
  // shoots omega times the unshot and leaves (1 - omega) times it: exactly all and none for 1.
  const double omega = settings_.overrelaxation;
  for (size_t s = 0; s < plan.shots.size(); ++s) {
    const uint32_t i = plan.shots[s].shooter;
    shot_light_[s] = unshot_[i] * scene_.patches[i].area * omega;
    unshot_[i] = omega == 1 ? Rgb{} : unshot_[i] * (1 - omega);
  }
}

void ProgressiveSolver::ApplyShot(const RoundPlan& plan, size_t s,
                                  std::span<const BatchResult> results) {
  const Shot& shot = plan.shots[s];
  const ShotHits hits = SumShotHits(results, &hit_weight_);
  const double total = double(sampler_.TotalWeight(shot.rays));
  if (plan.gather) {
    // Each gathering patch's radiosity from the state at the start of the round (all patches read
    // the same B until EndRound), so the order of patches does not matter.
    Rgb bounced;
    for (uint32_t j : hits.touched) {
      // With the direct light known, only light that bounced is gathered; else all of it.
      const Rgb seen =
          emitters_direct_ ? radiosity_[j] - scene_.patches[j].emission : radiosity_[j];
      bounced += seen * (double(hit_weight_[j]) / total);
      hit_weight_[j] = 0;
    }
    shot_light_[s] = bounced;
    return;
  }
  const Rgb power = shot_light_[s];
  // Southwell update: receiver j gets flux power * F_ij; it reflects rho_j of it, which raises
  // its radiosity and unshot radiosity by rho_j * flux / A_j (= rho_j * dB_i * F_ij * A_i / A_j).
  for (uint32_t j : hits.touched) {
    const Patch& receiver = scene_.patches[j];
    const Rgb flux = power * (double(hit_weight_[j]) / total);
    const Rgb reflected = receiver.reflectance * flux;
    const Rgb gain = reflected / receiver.area;
    radiosity_[j] += gain;
    unshot_[j] += gain;
    energy_.absorbed += (flux - reflected).Sum();
    hit_weight_[j] = 0;
  }
  energy_.escaped += power.Sum() * (double(hits.escaped) / total);
  energy_.absorbed += power.Sum() * (double(hits.back) / total);
}

void ProgressiveSolver::EndRound(const RoundPlan& plan) {
  if (plan.gather) {
    for (size_t s = 0; s < plan.shots.size(); ++s) {
      const uint32_t i = plan.shots[s].shooter;
      const Patch& p = scene_.patches[i];
      const Rgb direct = direct_.empty() ? Rgb{} : direct_[i];
      radiosity_[i] = p.emission + p.reflectance * (direct + shot_light_[s]);
    }
    // The unshot left (below the tolerance) is taken as absorbed: the account still balances.
    energy_.absorbed += SignedUnshotPower();
    std::fill(unshot_.begin(), unshot_.end(), Rgb{});
    energy_.unshot = 0;
  } else {
    energy_.unshot = TotalUnshotPower();
  }
  // The round's scratch goes: between rounds the solver holds its state only. (Swapped with
  // empty vectors: `= {}` would empty them and keep their memory.)
  std::vector<uint64_t>().swap(hit_weight_);
  std::vector<Rgb>().swap(shot_light_);
  rounds_done_ = plan.round + 1;
}

void ProgressiveSolver::Restore(uint32_t rounds_done, std::vector<Rgb> radiosity,
                                std::vector<Rgb> unshot, const EnergyAccount& energy) {
  rounds_done_ = rounds_done;
  radiosity_ = std::move(radiosity);
  unshot_ = std::move(unshot);
  energy_ = energy;
  energy_.unshot = TotalUnshotPower();
}

void ProgressiveSolver::StartFrom(std::vector<Rgb> radiosity, std::vector<Rgb> unshot) {
  radiosity_ = std::move(radiosity);
  unshot_ = std::move(unshot);
  gather_ = false;
  energy_.absorbed = energy_.emitted - energy_.escaped - SignedUnshotPower();
  energy_.unshot = TotalUnshotPower();
}

}  // namespace radfarm
