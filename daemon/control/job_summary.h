// What the control socket shows of a job that is not (or not only) in memory: its store record,
// the settings saved at submission, and the totals of its recorded rounds. Read on the store
// thread (ReadJobSummary), turned into the job object of docs/CONTROL.md on the loop thread.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "base/result.h"
#include "store/job_store.h"

namespace radfarm::daemon {

// The job's settings as the master keeps them in the jobs.settings column (JSON).
struct SubmittedSettings {
  double tolerance = 1e-3;
  uint64_t max_rays = 0;
  double max_seconds = 0;
  std::string sampler;
  uint64_t patches = 0;
  std::string scene;  // the OBJ path as given to `radfarm submit`

  std::string ToJson() const;
  static Result<SubmittedSettings> FromJson(const std::string& text);
};

struct JobSummary {
  store::JobRecord record;
  SubmittedSettings settings;
  uint32_t rounds = 0;  // recorded rounds
  uint64_t rays = 0;
  double seconds = 0;
  double unshot_fraction = 1;  // after the last recorded round
  // Why a finished job stopped, as its last checkpoint recorded it (jobs stored before schema 4
  // have none: StopReasonOf infers it then).
  std::optional<std::string> stop_reason;
};

// Store thread.
Result<JobSummary> ReadJobSummary(store::JobStore& store, const store::JobRecord& record);

// "converged", "ray budget" or "time budget" for a finished job: the recorded reason, else
// inferred from its totals.
std::string StopReasonOf(const JobSummary& summary);

}  // namespace radfarm::daemon
