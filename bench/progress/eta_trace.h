// One solve of a job as `radfarm render` runs it, with the ETA and progress `render` shows
// (core/progress_estimator.h, fed as cli/progress_reporter.cc feeds it) recorded after every round
// and every tenth of the final gather, against the time that was really left.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace radfarm::bench {

struct EtaPoint {
  uint32_t round = 0;          // rounds applied
  bool in_gather = false;      // taken during the final gather
  double seconds = 0;          // since the solve started
  double predicted_left = -1;  // the ETA shown; -1 when it showed "?"
  double actual_left = 0;      // the solve's end less `seconds`
  double fraction = 0;         // the bar
};

struct EtaTrace {
  std::string scene;
  uint64_t patches = 0;
  unsigned threads = 0;
  uint64_t rays = 0;
  double seconds = 0;  // the whole solve
  std::vector<EtaPoint> points;
  // Seconds per gather ray over seconds per shooting ray: as the probe measured it before round 1
  // (core/ray_cost_probe.h; 0 if it did not) and as the rounds then ran (0 without a gather).
  double gather_ray_cost_probed = 0;
  double gather_ray_cost_seen = 0;
};

// Loads and meshes the job file `job_path` and solves it on `threads` threads. Throws
// std::runtime_error with the loader's message.
EtaTrace TraceJob(const std::string& name, const std::string& job_path, unsigned threads);

}  // namespace radfarm::bench
