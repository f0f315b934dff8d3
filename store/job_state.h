// The lifecycle of a job in the store. SubmitJob() creates a job in `queued`; every later change
// goes through JobStore::SetJobState(id, to, error), which refuses any transition not drawn here
// (IsAllowedTransition) with an error naming both states. Edge labels are the `to` argument.
//
//                   +----------------- kQueued: requeue ------------------+
//                   v   (daemon restart, no agents; resumes from          |
//                       LoadLatestCheckpoint)                             |
//   SubmitJob() -> queued ------------- kRunning: started ------------> running --kDone--> done
//                   |  ^                (after NextRunnableJobs)          |  |   (converged or
//           kPaused |  | kQueued: resume                                  |  |    budget spent)
//                   v  |                                                  |  |
//                  paused <------------- kPaused ------------------------+  +--kFailed, error-->
//                                                                                        failed
//   running --kHeld: a store fault, reason--> held --kQueued: released or resumed--> queued
//                                               +----kPaused: an operator's pause--> paused
//
//   queued, running, paused, held ---------- kCancelled (reason optional) ----------> cancelled
//
// done, failed and cancelled are terminal: a retry is a new SubmitJob(). kFailed and kHeld require
// an error text (the reason), kCancelled and kPaused take an optional one, other transitions take
// none (and clear it). A held job was stopped by the master after a store fault (disk full, I/O
// error: HoldJob in job_transactions.h), not by an operator; it goes back to the queue by itself
// once the store writes again (ReleaseHeldJobs), or with `radfarm resume`; `radfarm pause` makes
// it an operator's pause, which waits for `resume`.
// Times: started_at is set on the first entry to running; finished_at on entry to a terminal state.
//
// An operator's command (`radfarm cancel|pause|resume`, ChangeJobState in job_transactions.h)
// takes these edges, and fewer: cancel -> kCancelled and pause -> kPaused wherever the diagram
// allows them; resume -> kQueued from paused or held only (a running job goes back to the queue
// only when the master restarts).
#pragma once

#include <optional>
#include <string_view>

namespace radfarm::store {

enum class JobState { kQueued, kRunning, kPaused, kHeld, kDone, kFailed, kCancelled };

// The name stored in the jobs.state column and shown to operators: "queued", "running", ...
std::string_view JobStateName(JobState state);
std::optional<JobState> ParseJobState(std::string_view name);

bool IsTerminal(JobState state);
bool IsAllowedTransition(JobState from, JobState to);

// What an operator asks of a job.
enum class JobCommand { kCancel, kPause, kResume };

// "cancel", "pause", "resume"; and the past participle, for messages: "cancelled", ...
std::string_view JobCommandName(JobCommand command);
std::string_view JobCommandDone(JobCommand command);
// The state the command moves a job to, and whether it may from `from` (the rules above).
JobState CommandTarget(JobCommand command);
bool IsAllowedCommand(JobState from, JobCommand command);

}  // namespace radfarm::store
