// FarmSim: a whole solve driven through RoundScheduler by simulated agents on a fake clock, the
// way the daemon's event loop will drive it. Agents compute their leases for real (BatchTracer)
// one at a time at a simulated speed, and can misbehave: die, hand leases back, stall, answer
// late, answer twice, or lie once.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "core/batch_tracer.h"
#include "core/patch_scene.h"
#include "core/progressive_solver.h"
#include "core/ray_caster.h"
#include "core/rgb.h"
#include "core/solver_settings.h"
#include "daemon/scheduler/round_scheduler.h"

namespace radfarm::scheduler::testing {

struct SimAgentSpec {
  double rays_per_second = 1e6;
  std::optional<Duration> dies_at;            // lost (OnAgentLost) at this simulated time
  std::optional<Duration> returns_leases_at;  // hands back everything it holds, once
  std::optional<Duration> stalls_at;          // from then on stall_factor times slower
  double stall_factor = 1e5;
  Duration result_delay = Duration::zero();  // added to every result's delivery
  bool sends_twice = false;                  // every result arrives twice
  std::optional<int> lies_on_result;         // this result (0-based) is corrupted
};

class FarmSim {
 public:
  static constexpr Duration kStep = std::chrono::milliseconds(10);

  FarmSim(const PatchScene& scene, const SolverSettings& settings,
          const std::vector<SimAgentSpec>& agents, const SchedulerOptions& options = {});

  // Runs rounds like the round driver (solve/round_driver.h) until converged (settings without
  // ray or time budgets) and returns the radiosity. Fails the test if a round does not finish
  // within `max_round_time`.
  std::vector<Rgb> Solve(uint32_t batch_rays, Duration max_round_time = std::chrono::seconds(3600));
  // Keeps agents delivering (nothing new is leased) for `duration`, so stragglers answer.
  void Drain(Duration duration);

  const RoundScheduler& scheduler() const { return scheduler_; }
  TimePoint now() const { return now_; }
  uint32_t rounds() const { return rounds_; }

 private:
  struct Pending {
    Assignment assignment;
    TimePoint deliver_at;
  };
  struct SimAgent {
    AgentId id = 0;
    SimAgentSpec spec;
    std::unique_ptr<BatchTracer> runner;
    std::deque<Pending> pending;  // in delivery order
    TimePoint busy_until;
    bool alive = true;
    bool returned = false;
    int results_sent = 0;
  };

  void Step(bool lease);
  void ApplyFaults(SimAgent& agent);
  void Deliver(SimAgent& agent);
  bool LeaseOne(SimAgent& agent);  // false: the scheduler had nothing for it

  const PatchScene& scene_;
  SolverSettings settings_;
  RayCaster caster_;
  ProgressiveSolver solver_;
  RoundScheduler scheduler_;
  std::vector<SimAgent> agents_;
  TimePoint start_{};
  TimePoint now_{};
  uint32_t rounds_ = 0;
};

}  // namespace radfarm::scheduler::testing
