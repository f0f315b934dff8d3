#include "tests/daemon/scheduler/farm_sim.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/solve_control.h"
#include "daemon/scheduler/result_intake.h"
#include "protocol/batch_convert.h"

namespace radfarm::scheduler::testing {

FarmSim::FarmSim(const PatchScene& scene, const SolverSettings& settings,
                 const std::vector<SimAgentSpec>& agents, const SchedulerOptions& options)
    : scene_(scene),
      settings_(settings),
      caster_(scene),
      solver_(scene, settings),
      scheduler_(options) {
  AgentId id = 100;
  for (const SimAgentSpec& spec : agents) {
    SimAgent& agent = agents_.emplace_back();
    agent.id = id++;
    agent.spec = spec;
    agent.runner = std::make_unique<BatchTracer>(scene_, caster_, solver_.sampler());
    scheduler_.AddAgent(agent.id);
  }
}

std::vector<Rgb> FarmSim::Solve(uint32_t batch_rays, Duration max_round_time) {
  // The master's stopping rules (no budgets here): until converged, the final gather included.
  while (!StopBeforeRound(solver_, settings_, 0, 0)) {
    const RoundPlan plan = solver_.PlanRound(batch_rays);
    if (plan.batches.empty()) break;
    EXPECT_TRUE(scheduler_.StartRound(plan, now_).ok());
    const TimePoint round_start = now_;
    while (!scheduler_.RoundComplete()) {
      if (now_ - round_start > max_round_time) {
        ADD_FAILURE() << "round " << plan.round << " did not finish";
        return solver_.radiosity();
      }
      Step(true);
    }
    Result<CompletedRound> done = scheduler_.TakeCompletedRound();
    EXPECT_TRUE(done.ok());
    solver_.ApplyRound(done->plan, done->results);
    ++rounds_;
  }
  return solver_.radiosity();
}

void FarmSim::Drain(Duration duration) {
  const TimePoint end = now_ + duration;
  while (now_ < end) Step(false);
}

void FarmSim::Step(bool lease) {
  now_ += kStep;
  for (SimAgent& agent : agents_) ApplyFaults(agent);
  for (SimAgent& agent : agents_) Deliver(agent);
  scheduler_.Tick(now_);
  // One lease per agent per pass, as agents asking in turn would get them.
  for (bool leased = lease; leased;) {
    leased = false;
    for (SimAgent& agent : agents_) leased = LeaseOne(agent) || leased;
  }
}

void FarmSim::ApplyFaults(SimAgent& agent) {
  if (!agent.alive) return;
  const Duration t = now_ - start_;
  if (agent.spec.dies_at && t >= *agent.spec.dies_at) {
    agent.alive = false;
    agent.pending.clear();
    scheduler_.OnAgentLost(agent.id);
    return;
  }
  if (agent.spec.returns_leases_at && !agent.returned && t >= *agent.spec.returns_leases_at) {
    agent.returned = true;
    std::vector<BatchId> ids;
    for (const Pending& p : agent.pending) ids.push_back(p.assignment.batch_id);
    scheduler_.ReturnLeases(agent.id, ids);
    agent.pending.clear();
    agent.busy_until = now_;
  }
}

void FarmSim::Deliver(SimAgent& agent) {
  while (agent.alive && !agent.pending.empty() && agent.pending.front().deliver_at <= now_) {
    const Assignment a = agent.pending.front().assignment;
    agent.pending.pop_front();
    const protocol::LeaseRef lease{1, a.batch_id, a.attempt_id};
    protocol::BatchOutcome message =
        protocol::MakeBatchOutcome(lease, agent.runner->Run(a.batch), 0.01);
    if (agent.spec.lies_on_result == agent.results_sent) ++message.escaped_rays;  // a lost ray
    ++agent.results_sent;
    const uint32_t patches = static_cast<uint32_t>(scene_.patches.size());
    const IntakeVerdict intake =
        SubmitBatchOutcome(scheduler_, agent.id, message, solver_.sampler(), patches, now_);
    // The daemon's part (daemon/agents/job_blocklist.h), played strictly: one lie blocklists the
    // agent.
    if (intake.verdict.reason == DropReason::kInvalid) {
      scheduler_.Blocklist(agent.id, now_ + std::chrono::hours(1));
    }
    if (agent.spec.sends_twice) {
      SubmitBatchOutcome(scheduler_, agent.id, message, solver_.sampler(), patches, now_);
    }
  }
}

bool FarmSim::LeaseOne(SimAgent& agent) {
  if (!agent.alive) return false;
  std::optional<Assignment> a = scheduler_.NextAssignment(agent.id, now_);
  if (!a) return false;
  double rate = agent.spec.rays_per_second;
  if (agent.spec.stalls_at && now_ - start_ >= *agent.spec.stalls_at) {
    rate /= agent.spec.stall_factor;
  }
  const auto compute = std::chrono::duration_cast<Duration>(
      std::chrono::duration<double>(a->batch.ray_count / rate));
  agent.busy_until = std::max(agent.busy_until, now_) + compute;
  agent.pending.push_back({*a, agent.busy_until + agent.spec.result_delay});
  return true;
}

}  // namespace radfarm::scheduler::testing
