// A fault campaign as code: a seeded random schedule of faults against a loopback farm
// (testing/loopback_farm.h) while jobs run, then a check of every job. The faults: agents
// SIGKILLed and restarted, SIGSTOPped and SIGCONTed, stopped (SIGTERM) and restarted; the master
// SIGKILLed and restarted on the same state directory and port; the state directory (a small
// tmpfs the campaign mounts) filled to ENOSPC and freed; the store file damaged before the first
// start; the master SIGKILLed and its store file cut short at a random byte before its restart
// (refused and restored from a copy, as an operator restores a backup, or taken if intact).
// The invariants: every job ends byte-identical to the reference (`radfarm render`) or failed
// with a message; every job submitted is listed once, none more.
//
// Shared by tests/farm/fault_campaign_test.cc (a small campaign in CI) and bench/faults (the long
// one behind docs/BENCHMARKS-faults.md). The same seed gives the same schedule of fault kinds,
// targets and delays; a failing campaign re-runs with it.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "testing/loopback_farm.h"

namespace radfarm::testing {

struct FaultPlan {
  uint32_t seed = 1;
  unsigned agents = 3;
  int jobs = 2;  // submitted during the campaign; more if all finish while faults remain
  int agent_faults = 10;
  int master_kills = 3;
  int disk_fills = 0;  // > 0 mounts a tmpfs of `state_dir_bytes` as the master's state dir
  int store_truncations = 0;  // master SIGKILLs whose restart finds the store file cut short
  bool damage_store_at_start = true;
  uint64_t state_dir_bytes = 64ull << 20;
  std::string job_file;  // absolute path of the scene or job file every job renders
  std::vector<std::string> job_flags;
  std::vector<std::string> master_flags;     // e.g. short heartbeats and --hold-retry-ms
  std::chrono::milliseconds max_gap{300};    // random pause between two faults
  std::chrono::milliseconds max_stop{2500};  // how long a SIGSTOPped agent stays stopped
  std::chrono::milliseconds job_timeout{std::chrono::minutes(5)};  // after the last fault
};

struct CampaignOutcome {
  std::map<std::string, int> faults;  // by kind: agent_kill, agent_stop, agent_restart, ...
  int jobs_submitted = 0;
  int jobs_listed = 0;
  int byte_identical = 0;
  int failed_with_message = 0;
  int wrong_bytes = 0;  // done, but not the reference's bytes
  int unfinished = 0;   // neither done nor failed by the deadline, or failed without a message
  int lost = 0;         // submitted, not listed
  int duplicated = 0;   // listed twice, or listed but never submitted
  double wall_seconds = 0;
  std::vector<std::string> problems;  // one line each, for the test's or the bench's report

  bool ok() const {
    return problems.empty() && wrong_bytes == 0 && unfinished == 0 && lost == 0 &&
           duplicated == 0 && jobs_listed == jobs_submitted;
  }
};

// Runs the campaign in `dir` (which must exist and be empty) against `reference_patches` (the
// patches.csv `radfarm render` writes for the same job). `say` receives one line per fault, so
// that a failing run shows where it was.
CampaignOutcome RunFaultCampaign(const FarmPrograms& programs, const std::string& dir,
                                 const FaultPlan& plan, const std::string& reference_patches,
                                 const std::function<void(const std::string&)>& say);

}  // namespace radfarm::testing
