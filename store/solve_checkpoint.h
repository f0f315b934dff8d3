// Between a solve's state at a round boundary (solve/solve_state.h) and the store's checkpoint of
// it: the master's RunningJob and `radfarm render --db` save and resume through these two, so a
// state saved by either resumes in either.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "core/patch_scene.h"
#include "solve/solve_state.h"
#include "store/job_store.h"

namespace radfarm::store {

// The checkpoint of `state` for `job`; `scene_hash` names the refined scene (stored first) when
// the state is on a refined mesh. Moves the state's vectors.
Checkpoint CheckpointOf(JobId job, SolveState state, std::optional<std::string> scene_hash);

// The state to resume from `checkpoint`, with the totals of `rounds` up to its round
// (TotalsUpToRound). `refined_scene`: the decoded scene the checkpoint's scene_hash names, or
// null; the caller keeps it alive while the state is used.
SolveState ResumeStateOf(const Checkpoint& checkpoint, std::span<const RoundRecord> rounds,
                         const PatchScene* refined_scene);

}  // namespace radfarm::store
