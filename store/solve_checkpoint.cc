#include "store/solve_checkpoint.h"

#include <utility>

#include "store/round_totals.h"

namespace radfarm::store {

Checkpoint CheckpointOf(JobId job, SolveState state, std::optional<std::string> scene_hash) {
  Checkpoint c;
  c.job = job;
  c.round = state.round;
  c.rounds_done = state.rounds_done;
  c.radiosity = std::move(state.radiosity);
  c.unshot = std::move(state.unshot);
  c.energy = state.energy;
  c.scene_hash = std::move(scene_hash);
  c.refine_points = state.next_point;
  c.stop_reason = std::move(state.stop);
  return c;
}

SolveState ResumeStateOf(const Checkpoint& checkpoint, std::span<const RoundRecord> rounds,
                         const PatchScene* refined_scene) {
  SolveState state;
  state.round = checkpoint.round;
  state.rounds_done = checkpoint.rounds_done;
  state.radiosity = checkpoint.radiosity;
  state.unshot = checkpoint.unshot;
  state.energy = checkpoint.energy;
  state.totals = TotalsUpToRound(rounds, checkpoint.round).solve_totals();
  state.refined_scene = refined_scene;
  state.next_point = checkpoint.refine_points;
  state.stop = checkpoint.stop_reason;
  return state;
}

}  // namespace radfarm::store
