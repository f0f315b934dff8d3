// One scaling measurement: a real radfarmd (a process, started fresh), N simulated agents
// (farmsim/) connected to it, one job submitted with the real CLI and run to its end.
//
// The job: scenes/furnace.obj (a closed cube, every face emitting with reflectance 0.9) meshed
// into 384 patches, Sobol, with shot_rays and a tolerance that stop it after exactly `rounds`
// rounds: the simulated results put every ray on a patch of reflectance 0.9, so the unshot power
// falls by exactly 0.9 a round and every round keeps all 384 patches shooting.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/farm/farm_checks.h"
#include "farmsim/idle_split.h"

namespace radfarm::bench {

struct ScalingCase {
  size_t agents = 10;
  double rays_per_second = 16384;  // each simulated agent's speed
  double latency_ms = 0;           // added one way, to every frame each way
  uint64_t shot_rays = 0;          // rays of the first round
  int rounds = 4;
  std::vector<std::string> master_flags;  // extra radfarmd flags
};

struct ScalingSample {
  uint64_t job_rays = 0;  // the job's rays (radfarm status), accepted work
  uint32_t rounds = 0;
  uint64_t batches = 0;        // results the agents sent
  uint64_t computed_rays = 0;  // rays of those results (re-issued batches count twice)
  double wall_seconds = 0;     // first assignment to the job's end (first Cancel), on the sockets
  double bytes_sent = 0, bytes_received = 0, scene_bytes = 0;  // by the agents, all frames
  double utilisation_mean = 0, utilisation_min = 0;            // busy / wall, over agents
  double efficiency = 0;                                       // (job rays / R) / (N * wall)
  double master_cpu_seconds = 0;          // radfarmd's CPU time over the whole run
  double master_connect_cpu_seconds = 0;  // of it: until every agent had authenticated
  // The same two for radfarmd's event-loop thread alone (its main thread: leases, results,
  // frames), without the compute and store threads' reductions, planning and SQLite.
  double master_loop_cpu_seconds = 0, master_loop_connect_cpu_seconds = 0;
  uint64_t frames = 0;                         // frames the agents sent and received
  double swarm_cpu_seconds = 0;                // the simulator's
  double mean_lateness = 0, max_lateness = 0;  // the simulator's timers
  double connect_seconds = 0;
  // Where the agents' idle time went (farmsim/idle_split.h): between rounds (from a
  // round's last result to the next round's first lease: reduction, planning, the lease's way
  // out) and within rounds (waiting for leases, round starts and tails).
  sim::IdleSplit idle;
  size_t agent_errors = 0;  // agents that closed during the job
  std::string first_error;

  double batches_per_second() const { return wall_seconds > 0 ? batches / wall_seconds : 0; }
  double bytes_per_ray() const {
    return job_rays ? (bytes_sent + bytes_received) / double(job_rays) : 0;
  }
  // Wire bytes per batch, the one-off scene fetch left out.
  double bytes_per_batch() const {
    return batches ? (bytes_sent + bytes_received - scene_bytes) / double(batches) : 0;
  }
};

// Throws std::runtime_error when the run fails (master, job or agents).
ScalingSample RunScalingCase(const FarmPrograms& programs, const std::string& scenes_dir,
                             const std::string& work_dir, const ScalingCase& c);

// Raises this process's open-file limit to its hard limit (children inherit it); returns the
// new soft limit.
uint64_t RaiseOpenFileLimit();

}  // namespace radfarm::bench
