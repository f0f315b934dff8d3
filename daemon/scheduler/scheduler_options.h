// Tuning of the scheduler. Every field has a working default; times are wall-clock.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

#include "daemon/scheduler/scheduler_types.h"

namespace radfarm::scheduler {

struct SchedulerOptions {
  // The batch time the master aims for, seen from the master: from handing out a lease to its
  // result. An agent holds about this much work (its smoothed rays/s times this), so a fast agent
  // holds more leases and a slow one is never flooded. Keep it within 100-500 ms.
  double target_lease_seconds = 0.5;
  // A lease is one attempt at one batch; the daemon sends an agent's new leases in one
  // LeaseAssignment frame of at most LeaseSizeOf() batches (protocol version 2).
  // Leases an agent holds before its first result is measured, and the cap for anyone.
  uint32_t initial_leases = 2;
  uint32_t max_leases_per_agent = 64;
  // Leases a measured agent holds beyond those that fill target_lease_seconds, so that its next
  // batch is already there when one finishes and it never idles for the round trip to the master
  // (result out, next lease back). radfarmd sets its own (daemon/master.cc).
  uint32_t spare_leases = 0;
  // Beyond spare_leases: this fraction of the target's leases again, so that an agent working
  // through one multi-batch lease already holds the next (radfarmd sets its own: daemon/master.cc).
  double spare_lease_fraction = 0;
  // Weight of the newest result in the smoothed throughput (exponential moving average).
  double throughput_smoothing = 0.3;
  // A lease is overdue after deadline_multiple times its expected time, at least deadline_floor;
  // an agent with no measurement yet is expected to take unmeasured_expected_seconds.
  double deadline_multiple = 4;
  Duration deadline_floor = std::chrono::seconds(2);
  double unmeasured_expected_seconds = 2;
  // The end game (the round's queue empty): an idle agent gets a copy of a running lease that has
  // taken this many times its expected time. 0: no end-game copies (only Tick's overdue ones).
  double end_game_copy_factor = 2;
  // The round's end: a measured agent that holds work gets another fresh batch only while all it
  // would then hold is done within this fraction of the time the round is predicted to need (the
  // rays of its batches not yet done over the measured agents' summed rays/s). Without it the
  // first agents asked fill their lease capacity, sized for a lease horizon, and a round shorter
  // than that horizon (a final gather) or its last part waits on them while others idle. An
  // agent the job has not measured yet holds at most its equal share of the round's batches not
  // done. 0: no cap. radfarmd sets its own (daemon/master.cc).
  double round_end_share = 0;
  // An agent measured here that holds less than this much work (its measured rays/s times it), and
  // no leases of other schedulers, may take fresh batches beyond its lease capacity
  // (round_end_share still applies). The capacity counts batches of the round's mean size, while a
  // round's tapered end is cut into pieces of a sixteenth of that: a capacity of them is less work
  // than the round trip to the master, so an agent ran dry for a round trip after each lease
  // there. 0: off. radfarmd sets its own (daemon/master.cc); the gather ahead leaves it off
  // (daemon/jobs/gather_ahead.cc).
  double min_held_seconds = 0;
  // Live attempts of one batch at most (the original plus speculative copies).
  uint32_t max_live_attempts = 2;
  // The first attempt id issued (ids then count up, wrap and skip 0): tests start near 2^32.
  uint32_t first_attempt_id = 1;
  // How long an agent blocklisted for a job gets none of its work (daemon/agents/job_blocklist.h).
  Duration blocklist_duration = std::chrono::minutes(10);  // MasterConfig::blocklist_seconds
  // The next round's last rays cut finer (core/batch.h TaperBatches) in this many ways per known
  // agent: near the round's end a batch holds at most the rays after it over that many, so the
  // agents' last leases finish close together. One way cuts too late to even out the agents' held
  // work; many more cost frames for nothing. 0: no taper.
  double taper_ways_per_agent = 3;
  // The final gather's first rays, at most this many, are leased to agents with nothing else to
  // do while the shooting rounds run (daemon/jobs/gather_ahead.h). 0: off. radfarmd: MasterConfig's
  // gather_ahead_rays.
  uint64_t gather_ahead_rays = 0;
  // SuggestedBatchRays() bounds.
  uint32_t min_batch_rays = 256;
  uint32_t max_batch_rays = 1 << 20;
  uint32_t default_batch_rays = 4096;
};

// The taper a round planned for `agents` agents gets: taper_ways_per_agent ways each.
inline uint32_t TaperWays(const SchedulerOptions& options, size_t agents) {
  const double ways = std::round(options.taper_ways_per_agent * double(agents));
  return static_cast<uint32_t>(std::clamp(ways, 0.0, double(std::numeric_limits<uint32_t>::max())));
}

}  // namespace radfarm::scheduler
