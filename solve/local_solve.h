// Local solves: RoundDriver's rounds (round_driver.h) with the batches computed on this machine's
// threads. `radfarm render` runs SolveRefining; tests and benchmarks of the solver alone run Solve
// on a bare scene. The farm master computes small rounds with LocalBatches too.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "base/result.h"
#include "core/batch.h"
#include "core/batch_tracer.h"
#include "core/patch_scene.h"
#include "core/round_reduction.h"
#include "core/solver_settings.h"
#include "core/thread_pool.h"
#include "core/warm_start.h"
#include "mesh/patch_mesh.h"
#include "mesh/refine_settings.h"
#include "solve/round_driver.h"
#include "solve/solve_state.h"

namespace radfarm {

// Rays per batch in local solves. Any value gives the same result (see batch.h); this one keeps
// batches long enough to amortise scheduling and short enough to balance threads.
inline constexpr uint32_t kLocalBatchRays = 4096;

// Computes a round's batches on a thread pool, a BatchTracer per worker, for a driver's current
// scene (rebuilt when a refinement step replaces it).
class LocalBatches {
 public:
  explicit LocalBatches(ThreadPool& pool) : pool_(pool) {}
  // The round's results, all of them (the master's small rounds).
  std::vector<BatchResult> Run(RoundDriver& driver, const RoundPlan& plan);
  // The round's results folded into `reduction` (RoundDriver::Reduction) as they come;
  // `on_batch` (optional) after each batch with the round's rays computed so far, on a worker
  // thread, one call at a time.
  void Reduce(RoundDriver& driver, const RoundPlan& plan, RoundReduction& reduction,
              const std::function<void(uint64_t rays_done)>& on_batch = {});
  // Traces `batches` on the pool and throws their results away (RoundDriver::MeasureGatherRayCost).
  void TraceOnly(RoundDriver& driver, const std::vector<Batch>& batches);
  // The tracers of the driver's current scene (and its ray caster's BVH), if not made yet: the
  // calls above make them; a caller that times a trace makes them first.
  void Prepare(RoundDriver& driver);

 private:
  ThreadPool& pool_;
  const RoundDriver* driver_ = nullptr;
  uint32_t generation_ = 0;
  std::vector<std::unique_ptr<BatchTracer>> tracers_;
};

struct RefiningSolveResult {
  std::unique_ptr<PatchMesh> mesh;  // the mesh the solution belongs to
  SolveResult solution;
  uint64_t patches_before = 0;  // patches of the mesh given
  uint32_t refinements = 0;     // refinement steps that split at least one element
};

struct RefiningHooks {
  // Start from this state (`radfarm render --db`); its refined scene, if any, on `mesh`.
  const SolveState* resume = nullptr;
  // After every round, on the calling thread: the state at that boundary, taken after the
  // refinement step the round triggered.
  std::function<void(const SolveState&)> after_round;
  // While a round runs, after each batch, on a worker thread, one call at a time: for progress
  // within a long round (the final gather). It must be quick.
  std::function<void(const RoundRunning&)> during_round;
  // Seconds already spent on this job before the solve (reading and meshing the scene): they
  // count toward the time budget (max_seconds), not toward the solve's own seconds.
  double seconds_spent_before = 0;
  // Once the solver has started (the direct light computed, or the resumed state restored), with
  // the seconds that took and the shadow rays the direct light cast (ProgressiveSolver::
  // start_rays: they count against the ray budget).
  std::function<void(double seconds, uint64_t shadow_rays)> after_start;
  // Traces the direct-light start (core/direct_start.h); empty: on the solve's own threads. A
  // re-bake whose lights did not change gives back the previous start's.
  StartLightSource start;
  // A re-bake (`radfarm render --from`): the previous solution of the same patches the solve
  // starts from (RoundDriver::WarmStart). Not with refinement or `resume`.
  const PreviousPatchValues* previous = nullptr;
};

// Solves `mesh` with adaptive refinement as `refine` says (off: the mesh as given) until a
// stopping rule holds. `on_round` (optional) after every round, on the calling thread.
// Errors: refinement settings out of range (the message names the job file key); a resume state
// that does not fit the mesh.
Result<RefiningSolveResult> SolveRefining(
    PatchMesh mesh, const SolverSettings& settings, const RefineSettings& refine,
    const std::function<void(const RoundProgress&)>& on_round = {},
    const RefiningHooks& hooks = {});

// Solves a bare scene (no refinement), from `resume` if given (its sizes must fit the scene).
SolveResult Solve(const PatchScene& scene, const SolverSettings& settings,
                  const std::function<void(const RoundProgress&)>& on_round = {},
                  const SolveState* resume = nullptr,
                  const std::function<void(const SolveState&)>& after_round = {});

}  // namespace radfarm
