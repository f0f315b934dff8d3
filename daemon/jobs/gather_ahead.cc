#include "daemon/jobs/gather_ahead.h"

#include <algorithm>
#include <memory>

namespace radfarm::daemon {

std::optional<RoundPlan> GatherAhead::Plan(const ProgressiveSolver& solver, BatchSizing sizing,
                                           uint64_t max_rays) {
  RoundPlan plan = solver.PlanPendingGather(sizing.batch_rays);
  if (plan.batches.empty()) return std::nullopt;
  // As RunningJob::PlanNext cuts a round, so that the gather round's batches are these.
  TaperBatches(sizing.taper_ways, TaperFloor(sizing.batch_rays), &plan.batches);
  uint64_t rays = 0;
  size_t fit = 0;
  while (fit < plan.batches.size() && rays + plan.batches[fit].ray_count <= max_rays) {
    rays += plan.batches[fit++].ray_count;
  }
  if (fit == 0) return std::nullopt;
  plan.batches.resize(fit);
  plan.shots.clear();  // the scheduler leases batches; the solver never sees this plan
  plan.rays = rays;
  plan.round = kGatherRound;
  return plan;
}

Result<std::unique_ptr<GatherAhead>> GatherAhead::Start(RoundPlan plan, BatchSizing sizing,
                                                        const scheduler::SchedulerOptions& options,
                                                        scheduler::TimePoint now,
                                                        std::span<const uint64_t> agents) {
  // No copies of a lease: one that looks slow is queued behind its agent's round work (it goes
  // out when no round has more for that agent), and a copy would be the same rays twice.
  scheduler::SchedulerOptions own = options;
  own.end_game_copy_factor = 0;
  own.max_live_attempts = 1;
  // Nor beyond the capacity: with min_held_seconds here, farm_bench's agents computed 2.4 % of a
  // job's rays twice at 10 agents (0.1 % without).
  own.min_held_seconds = 0;
  std::unique_ptr<GatherAhead> ahead(new GatherAhead(sizing, own));
  for (uint64_t agent : agents) ahead->scheduler_.AddAgent(agent);
  RADFARM_RETURN_IF_ERROR(ahead->scheduler_.StartRound(std::move(plan), now));
  return ahead;
}

void GatherAhead::NoteAccepted(scheduler::BatchId batch, const std::string& agent) {
  agents_.insert_or_assign(scheduler::BatchIndex(batch), agent);
}

GatherAhead::Adopted GatherAhead::Adopt(const RoundPlan& round, std::span<const uint32_t> skip) {
  Adopted adopted;
  std::vector<uint32_t> done(skip.begin(), skip.end());
  std::sort(done.begin(), done.end());
  std::vector<uint32_t> indices;
  indices.reserve(agents_.size());
  for (const auto& [index, agent] : agents_) indices.push_back(index);
  std::sort(indices.begin(), indices.end());
  for (uint32_t index : indices) {
    if (index >= round.batches.size()) continue;
    if (std::binary_search(done.begin(), done.end(), index)) continue;
    const scheduler::BatchId id = scheduler::MakeBatchId(kGatherRound, index);
    const Batch* mine = scheduler_.FindBatch(id);
    if (mine == nullptr || !(*mine == round.batches[index])) {
      continue;  // planned differently (other batch sizes): computed again
    }
    std::optional<BatchResult> result = scheduler_.TakeResult(id);
    if (!result) continue;
    adopted.results.emplace_back(index, std::move(*result));
    adopted.agents.emplace_back(index, agents_.at(index));
  }
  agents_.clear();
  // The leases still out: their results go on to the round (OnResult).
  for (uint32_t index = 0; index < round.batches.size(); ++index) {
    if (scheduler_.HasLiveLease(scheduler::MakeBatchId(kGatherRound, index))) {
      adopted.in_flight.push_back(index);
    }
  }
  // Those never leased are the round's to lease, in its own order.
  (void)scheduler_.TakeQueued();
  adopted_ = true;
  return adopted;
}

std::vector<uint32_t> GatherAhead::TakeReturned() {
  if (!adopted_) return {};
  return scheduler_.TakeQueued();
}

}  // namespace radfarm::daemon
