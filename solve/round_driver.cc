#include "solve/round_driver.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "core/display_budget.h"
#include "core/solve_control.h"

namespace radfarm {

RoundDriver::RoundDriver(const SolverSettings& settings, ThreadPool* pool)
    : settings_(settings), pool_(pool) {}

RoundDriver::~RoundDriver() {
  // The caster and the solver refer to the scene: let them go first.
  caster_.reset();
  solver_.reset();
}

Result<std::unique_ptr<RoundDriver>> RoundDriver::Start(
    PatchMesh mesh, const SolverSettings& settings, const RefineSettings& refine,
    const SolveState* resume, ThreadPool& pool, StartLightSource start, LightScoreSource scores) {
  std::unique_ptr<RoundDriver> driver(new RoundDriver(settings, &pool));
  driver->start_ = std::move(start);
  driver->scores_ = std::move(scores);
  driver->mesh_ = std::make_unique<PatchMesh>(std::move(mesh));
  if (refine.enabled) {
    Result<RefinementSchedule> schedule = RefinementSchedule::Create(
        refine, *driver->mesh_, settings.shot_rays, resume != nullptr ? resume->next_point : 0);
    if (!schedule) return Error{schedule.error()};
    driver->schedule_.emplace(std::move(*schedule));
  } else if (resume != nullptr && resume->refined_scene != nullptr) {
    return Error{"cannot resume an unrefined solve on a refined mesh"};
  }
  if (resume != nullptr && resume->refined_scene != nullptr) {
    const PatchScene& stored = *resume->refined_scene;
    PatchMesh rebuilt = driver->mesh_->Rebuilt(PatchMesh::PiecesOf(stored), &pool);
    if (rebuilt.patch_scene().patches.size() != stored.patches.size()) {
      return Error{"the refined mesh to resume on has " + std::to_string(stored.patches.size()) +
                   " elements, rebuilt it has " +
                   std::to_string(rebuilt.patch_scene().patches.size())};
    }
    *driver->mesh_ = std::move(rebuilt);
    driver->refined_ = true;
  }
  driver->scene_ = &driver->mesh_->patch_scene();
  driver->RebuildSolver();
  if (resume != nullptr) {
    if (Status s = driver->Resume(*resume); !s) return Error{s.error()};
  } else if (driver->schedule_) {
    std::optional<RefinementStep> step = driver->schedule_->BeforeFirstRound(
        *driver->mesh_, *driver->solver_, driver->caster(), pool, driver->scores_);
    if (step) driver->Install(std::move(*step));
  }
  return driver;
}

std::unique_ptr<RoundDriver> RoundDriver::Start(const PatchScene& scene,
                                                const SolverSettings& settings,
                                                const SolveState* resume) {
  std::unique_ptr<RoundDriver> driver(new RoundDriver(settings, nullptr));
  driver->scene_ = &scene;
  driver->RebuildSolver();
  if (resume != nullptr) {
    // A bare scene's caller holds its own states: one that does not fit is its bug.
    if (Status s = driver->Resume(*resume); !s) throw std::invalid_argument(s.error());
  }
  return driver;
}

Result<std::unique_ptr<RoundDriver>> RoundDriver::StartOwning(PatchScene scene,
                                                              const SolverSettings& settings,
                                                              const SolveState* resume,
                                                              StartLightSource start) {
  if (resume != nullptr && resume->refined_scene != nullptr) {
    return Error{"cannot resume an unrefined solve on a refined mesh"};
  }
  std::unique_ptr<RoundDriver> driver(new RoundDriver(settings, nullptr));
  driver->start_ = std::move(start);
  driver->owned_scene_ = std::make_unique<const PatchScene>(std::move(scene));
  driver->scene_ = driver->owned_scene_.get();
  driver->RebuildSolver();
  if (resume != nullptr) {
    if (Status s = driver->Resume(*resume); !s) return Error{s.error()};
  }
  return driver;
}

Status RoundDriver::Resume(const SolveState& state) {
  if (state.radiosity.size() != scene_->patches.size()) {
    return Error{"the state to resume holds " + std::to_string(state.radiosity.size()) +
                 " elements, the mesh " + std::to_string(scene_->patches.size())};
  }
  solver_->Restore(state.rounds_done, state.radiosity, state.unshot, state.energy);
  totals_ = state.totals;
  last_round_ = state.round;
  last_shooters_ = state.shooters;
  stop_ = state.stop;
  return Ok{};
}

Status RoundDriver::WarmStart(const PreviousPatchValues& previous) {
  const size_t n = scene_->patches.size();
  for (const std::vector<Rgb>* v :
       {&previous.radiosity, &previous.unshot, &previous.emission, &previous.reflectance}) {
    if (v->size() != n) {
      return Error{"the previous solution holds " + std::to_string(v->size()) +
                   " patches, the mesh " + std::to_string(n)};
    }
  }
  if (!previous.direct.empty() && previous.direct.size() != n) {
    return Error{"the previous solution's direct light does not fit the mesh"};
  }
  uint32_t black = 0;
  std::optional<WarmState> warm =
      WarmStartOf(*scene_, solver_->direct_light(), solver_->emitters_direct(), previous, &black);
  if (!warm) {
    return Error{"patch " + std::to_string(black) +
                 " was black and now reflects: the light it received was not recorded, so only a "
                 "full render can light it"};
  }
  solver_->StartFrom(std::move(warm->radiosity), std::move(warm->unshot));
  return Ok{};
}

std::optional<uint64_t> RoundDriver::BudgetRaysLeft() const {
  if (budget_.max_rays == 0) return std::nullopt;
  return budget_.max_rays - std::min(budget_.max_rays, RaysSpent());
}

std::optional<double> RoundDriver::BudgetSecondsLeft(double seconds) const {
  if (!(budget_.max_seconds > 0)) return std::nullopt;
  return std::max(0.0, budget_.max_seconds - seconds);
}

std::optional<RoundPlan> RoundDriver::PlanNext(uint32_t batch_rays, double seconds,
                                               double rays_per_second) {
  if (stop_) return std::nullopt;
  // The start's shadow rays are spent from the same budget as the rounds' rays.
  const uint64_t spent = RaysSpent();
  stop_ = StopBeforeRound(*solver_, budget_, spent, seconds);
  if (stop_) return std::nullopt;
  uint64_t cap = NextRoundRayCap(budget_, spent);
  // The pace is the shooting rounds'; a gather ray costs MeasureGatherRayCost's ratio of one.
  const bool gather_next = solver_->GatherNext();
  if (gather_next && gather_ray_cost_ && *gather_ray_cost_ > 0) {
    rays_per_second /= *gather_ray_cost_;
  }
  const uint64_t time_cap = TimeRayCap(budget_, seconds, rays_per_second);
  time_capped_ = time_cap > 0 && (cap == 0 || time_cap < cap);
  if (time_capped_) cap = time_cap;
  // Under a budget, a shooting round gets its share of what is left (PacedRoundCap) where the
  // rounds to come would not fit at full strength.
  const uint64_t left = cap;
  if (left > 0 && !gather_next) {
    const ProgressiveSolver::RoundSize next = solver_->NextShootingRound();
    const uint64_t paced = PacedRoundCap(next.rays, next.power, solver_->UnshotFraction(),
                                         budget_.tolerance, solver_->EstimatedCarry(), left);
    if (paced > 0) cap = std::min(cap, paced);
  }
  RoundPlan plan = solver_->PlanRound(batch_rays, cap);
  if (cap < left) {
    if (plan.rays < left) {
      plan.capped = false;  // paced: not the budget's last round, the solve goes on after it
    } else {
      plan = solver_->PlanRound(batch_rays, left);  // a ray a shot at least: the last round
    }
  }
  if (plan.batches.empty()) {
    // Nothing left to shoot, or a gather that cannot give each patch a ray in the time left.
    stop_ = time_capped_ ? kStopTimeBudget : kStopConverged;
    return std::nullopt;
  }
  return plan;
}

AppliedRound RoundDriver::Apply(const RoundPlan& plan, const std::vector<BatchResult>& results,
                                double seconds) {
  uint64_t escaped_rays = 0, back_rays = 0;
  for (const BatchResult& r : results) {
    escaped_rays += r.escaped_rays;
    back_rays += r.back_rays;
  }
  solver_->ApplyRound(plan, results);
  return AfterApply(plan, escaped_rays, back_rays, seconds);
}

std::unique_ptr<RoundReduction> RoundDriver::Reduction(const RoundPlan& plan) {
  return std::make_unique<RoundReduction>(*solver_, plan);
}

AppliedRound RoundDriver::Apply(const RoundPlan& plan, RoundReduction& reduction, double seconds) {
  reduction.Finish();
  return AfterApply(plan, reduction.escaped_rays(), reduction.back_rays(), seconds);
}

AppliedRound RoundDriver::AfterApply(const RoundPlan& plan, uint64_t escaped_rays,
                                     uint64_t back_rays, double seconds) {
  AppliedRound applied;
  applied.escaped_rays = escaped_rays;
  applied.back_rays = back_rays;
  totals_.rays += plan.rays;
  totals_.escaped_rays += applied.escaped_rays;
  totals_.backface_hits += applied.back_rays;
  totals_.seconds = seconds;
  last_round_ = plan.round;
  last_shooters_ = static_cast<uint32_t>(plan.shots.size());
  applied.unshot_fraction = solver_->UnshotFraction();
  applied.unshot_power = solver_->energy().unshot;
  applied.gather_rays_left = solver_->PendingGatherRays();
  stop_ = StopAfterRound(plan, *solver_, budget_);
  if (stop_ && time_capped_) stop_ = kStopTimeBudget;
  // Refinement between rounds: only when the solve goes on.
  if (!stop_ && schedule_ && schedule_->PointPassed(*solver_)) {
    const auto start = std::chrono::steady_clock::now();
    std::optional<RefinementStep> step =
        schedule_->AfterRound(*mesh_, *solver_, caster(), *pool_, scores_);
    if (step) {
      Install(std::move(*step));
      applied.refined = true;
    }
    applied.refine_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return applied;
}

SolveState RoundDriver::State() const {
  SolveState state;
  state.round = last_round_;
  state.rounds_done = solver_->rounds_done();
  state.radiosity = solver_->radiosity();
  state.unshot = solver_->unshot();
  state.energy = solver_->energy();
  state.totals = totals_;
  state.shooters = last_shooters_;
  state.refined_scene = refined_ ? scene_ : nullptr;
  state.refinements = refinements_;
  state.next_point = schedule_ ? static_cast<uint32_t>(schedule_->next_point()) : 0u;
  state.stop = stop_;
  return state;
}

SolveResult RoundDriver::Finish(double seconds, uint32_t threads) const {
  SolveTotals totals = totals_;
  totals.seconds = seconds;
  SolveResult out;
  out.stats = StatsOf(totals, solver_->energy());
  out.stats.start_rays = solver_->start_rays();
  out.stats.rounds = solver_->rounds_done();
  out.stats.patches = scene_->patches.size();
  out.stats.unshot_fraction = solver_->UnshotFraction();
  out.stats.threads = threads;
  out.stats.seed = settings_.seed;
  out.stats.sampler = std::string(SamplerName(settings_.sampler));
  out.stats.stop_reason = stop_.value_or(kStopConverged);
  out.radiosity = solver_->radiosity();
  out.unshot = solver_->unshot();
  out.direct_light = solver_->direct_light();
  out.emitters_direct = solver_->emitters_direct();
  out.punctual_power = solver_->punctual_power();
  return out;
}

void RoundDriver::MeasureGatherRayCost(const RoundPlan& plan, uint32_t batch_rays,
                                       const RayCostTracer& trace) {
  if (gather_ray_cost_tried_ || plan.gather || !solver_->GatherPending()) return;
  gather_ray_cost_tried_ = true;
  const uint64_t gathering = solver_->GatheringPatches();
  if (gathering == 0) return;
  const uint64_t gather_rays = solver_->PendingGatherRays();
  RayCostProbe probe;
  probe.rays_per_kind = std::clamp<uint64_t>(gather_rays / 200, 8192, 65536);
  const RayCostSamples samples =
      SampleRayCosts(*scene_, plan, gather_rays / gathering, batch_rays, probe.rays_per_kind);
  gather_ray_cost_ = GatherRayCostRatio(samples, trace, probe.passes);
}

RoundProgress RoundDriver::Progress(const RoundPlan& plan, const AppliedRound& applied) const {
  RoundProgress progress{
      solver_->rounds_done(), totals_.rays,       totals_.seconds, applied.unshot_fraction,
      settings_.tolerance,    &solver_->energy(), plan.gather,     solver_->PendingGatherRays()};
  progress.gather_ray_cost = gather_ray_cost_.value_or(0);
  progress.display_rays = display_forecast_;
  return progress;
}

const RayCaster& RoundDriver::caster() {
  if (!caster_) caster_ = std::make_unique<RayCaster>(*scene_);
  return *caster_;
}

void RoundDriver::Install(RefinementStep step) {
  caster_.reset();
  solver_.reset();  // they refer to the old mesh's scene
  *mesh_ = std::move(step.mesh);
  scene_ = &mesh_->patch_scene();
  RebuildSolver();
  RestoreStep(step, *solver_);
  refined_ = true;
  ++refinements_;
}

SolverSettings RoundDriver::PhaseSettings() const {
  return schedule_ ? schedule_->SolverSettingsNow(settings_, scene_->patches.size()) : settings_;
}

void RoundDriver::RebuildSolver() {
  solver_ = std::make_unique<ProgressiveSolver>(*scene_, PhaseSettings(), start_);
  budget_ = SolveBudget(*scene_, settings_);
  display_forecast_ = DisplayRaysForecast(*scene_, settings_, solver_->start_rays());
}

}  // namespace radfarm
