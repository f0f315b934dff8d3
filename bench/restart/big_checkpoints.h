// What checkpoints cost a big job (at 10^6 patches less than 5% of a round, and a
// SIGKILLed master resumes byte-identical). The Cornell box meshed at `patch_size` is solved
//   - by `radfarm render --db` (checkpoints on its main thread, between rounds),
//   - by a loopback farm (radfarmd, 2 one-thread agents) without kills,
//   - by the same farm with the master SIGKILLed once after its first checkpoint, and restarted,
// and each round's wall time is set beside its checkpoint's bytes and times: radfarmd's from the
// job object of its control socket (`radfarm status --json`: last_checkpoint, looked at every
// 100 ms), render's from the line it prints for each checkpoint, the rounds' from their rows in the
// job store. The killed run must end with the same patches.csv as the farm run without kills and
// as render.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "testing/loopback_farm.h"

namespace radfarm::bench {

// Starts `farm`'s master with `flags` and `agents` one-thread agents, waits for them to connect
// and returns the address a restarted master must listen on to keep its port. Throws
// std::runtime_error when the master does not start or the agents do not connect.
std::string StartMasterAndAgents(testing::LoopbackFarm& farm, const std::vector<std::string>& flags,
                                 unsigned agents);

struct BigJobOptions {
  double patch_size = 1.45;      // mm: 1,046,925 patches
  uint64_t rays = 50000000;      // the job's ray budget
  uint64_t shot_rays = 0;        // [solver] shot_rays; 0: the default (384 a patch)
  unsigned agents = 2;           // one thread each
  std::string checkpoint_flags;  // extra radfarmd flags, space-separated (e.g. --checkpoint-keep 2)
};

// Runs the three jobs, prints a table and returns the raw figures. Throws std::runtime_error when
// a job fails or the killed run's bytes differ.
nlohmann::json MeasureBigJobCheckpoints(const BigJobOptions& options);

}  // namespace radfarm::bench
