// An office of small machines emulated on one box (office_bench, tests/testing): every process runs
// in a cpu group of its own (testing/cpu_cap.h) capped at `share` of a core. One machine is
// `radfarm render --threads 1`; the farm is radfarmd, N radfarm-agents with `--threads 1` and the
// `radfarm` client that submits, polls and fetches. Each step throws std::runtime_error (with the
// tail of the master's log where there is one) when a process fails or outlives `timeout`, and
// leaves no process or group behind.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "testing/cpu_cap.h"
#include "testing/loopback_farm.h"

namespace radfarm::testing {

// The outputs compared byte for byte between the farm and one machine.
inline const std::vector<std::string> kComparedOutputs = {"image.png", "radiosity.ply", "lit.glb",
                                                          "patches.csv"};

struct OfficeSetup {
  testing::CpuController cpu;
  testing::FarmPrograms programs;
  double share = 0.3;                          // of one core, for every process
  std::chrono::seconds timeout{3600};          // for any one command or job
  std::string job_file;                        // a job (.toml) or scene file
  std::vector<std::string> flags;              // given to both render and submit
  std::vector<std::string> master_flags = {};  // radfarmd's, after `--log-level warning`
};

// `radfarm render JOB --threads 1 --out OUT_DIR FLAGS` in a group of its own.
struct MachineRun {
  double seconds = 0;      // the whole command
  double cpu_seconds = 0;  // user + system
};
MachineRun RunOneMachine(const OfficeSetup& setup, const std::string& out_dir);

// The farm with `agents` agents from `radfarm submit` to `radfarm fetch --out OUT_DIR` done.
struct FarmRun {
  size_t agents = 0;
  double seconds = 0;        // submit to fetch done
  double job_seconds = 0;    // submit to the job seen done
  double fetch_seconds = 0;  // the fetch alone
  // CPU seconds (user + system) each part spent, read from /proc before the daemons stop: the
  // client's are every radfarm command's from submit to fetch, the status polls included.
  double master_cpu = 0, agents_cpu = 0, client_cpu = 0;
};
// `dir` (existing) keeps the farm's state and logs; the outputs go to out_dir.
FarmRun RunFarm(const OfficeSetup& setup, size_t agents, const std::string& dir,
                const std::string& out_dir);

// The names of kComparedOutputs whose bytes differ between two output directories (or that one
// of them lacks).
std::vector<std::string> DifferingOutputs(const std::string& a_dir, const std::string& b_dir);

// T(N) = serial + parallel / N fitted by least squares to (N, T) pairs; with one pair, all of it
// is taken as parallel.
struct AmdahlFit {
  double serial = 0, parallel = 0;
  double Predict(double n) const { return serial + parallel / n; }
};
AmdahlFit FitAmdahl(const std::vector<std::pair<double, double>>& n_and_seconds);

}  // namespace radfarm::testing
