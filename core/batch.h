// Batches: the unit of work the solver hands out, locally to threads and in the farm to agents.
//
// THE DETERMINISM CONTRACT (the farm relies on it; tests/core/determinism_test.cc checks it):
//  1. A round is planned from the solver state alone: which patches shoot and how many rays each
//     casts (RoundPlan). Planning is deterministic and sequential.
//  2. Ray k of shooter s in round r is RaySampler::Sample(patch s, s, r, k): a pure function of
//     (seed, round, shooter, k). A batch is the contiguous range [first_ray, first_ray + ray_count)
//     of one shooter's rays in one round, so its rays depend only on (seed, round, batch), never on
//     which thread or machine computes it, how often, or how the shot was cut into batches.
//  3. A batch's result is integer ray weights per hit patch, plus integer escaped and back-face
//     weights. Integer sums are exact in any order, so the reduction of a round (sum per shooter,
//     then the Southwell update in increasing shooter order, hits in increasing patch order) gives
//     bit-identical radiosity however the batches were scheduled.
//  4. The final gather's rays are keyed by kGatherRound, not by the round it runs in: its plan
//     depends on the mesh alone, so its batches can be traced before the round that folds them
//     is planned (the master leases them to idle agents during the shooting rounds).
#pragma once

#include <cstdint>
#include <vector>

namespace radfarm {

// The round key of every final-gather batch (Batch::round): no shooting round reaches it.
inline constexpr uint32_t kGatherRound = UINT32_MAX;

// The number of a round as people read it (logs, events, status, render's lines): from 1, the
// plan's round + 1. Plans, batch ids, the store's rows and checkpoints keep the plan's number.
inline uint32_t ShownRound(uint32_t plan_round) { return plan_round + 1; }

struct Batch {
  uint32_t round = 0;    // the rays' key: the round's number, or kGatherRound for the gather
  uint32_t shooter = 0;  // patch id
  uint64_t first_ray = 0;
  uint32_t ray_count = 0;
  bool operator==(const Batch&) const = default;
};

struct PatchHits {
  uint32_t patch = 0;
  uint64_t weight = 0;  // sum of the weights of the rays that hit the front of this patch
  bool operator==(const PatchHits&) const = default;
};

struct BatchResult {
  std::vector<PatchHits> hits;  // sorted by patch id, no zero weights
  uint64_t escaped_weight = 0;  // rays that left the scene
  uint64_t escaped_rays = 0;
  uint64_t back_weight = 0;  // rays that hit the back of a patch: absorbed there
  uint64_t back_rays = 0;
  bool operator==(const BatchResult&) const = default;
};

// Splits one shooter's shot of `rays` rays in `round` into batches of at most `batch_rays` rays.
void AppendShotBatches(uint32_t round, uint32_t shooter, uint64_t rays, uint32_t batch_rays,
                       std::vector<Batch>* batches);

// How a round's shots are cut into batches: batches of batch_rays, and with taper_ways > 0 the
// round's last rays cut finer (TaperBatches). The farm's master stores it with each result, so a
// restarted master plans the same batches (daemon/jobs/running_job.h).
struct BatchSizing {
  uint32_t batch_rays = 0;
  uint32_t taper_ways = 0;  // 0: no taper
  bool operator==(const BatchSizing&) const = default;
};

// The smallest batch TaperBatches cuts: a sixteenth of `batch_rays` (at least 1 ray).
uint32_t TaperFloor(uint32_t batch_rays);

// Guided self-scheduling at a round's end: a round is over when its last batch is, so the
// plan's last batches are cut finer, for agents that take them as they free up to finish close
// together. Walking back from the plan's end, each batch is cut into pieces of at most
// max(floor, rays after the piece / ways) rays, the first piece of a batch taking a remainder
// under `floor`; a batch that fits is left whole. Pieces stay in their batch's shot and in ray
// order, so the plan still covers every ray once, in shot order (ProgressiveSolver::ApplyRound
// sums a shot's hits as integers: the cut does not change the result, core/batch.h above).
// Deterministic in (batches, ways, floor); ways == 0 leaves the batches as they are.
void TaperBatches(uint32_t ways, uint32_t floor, std::vector<Batch>* batches);

}  // namespace radfarm
