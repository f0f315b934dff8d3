#include "store/job_state.h"

#include <array>

namespace radfarm::store {
namespace {

constexpr std::array<std::pair<JobState, std::string_view>, 7> kNames = {{
    {JobState::kQueued, "queued"},
    {JobState::kRunning, "running"},
    {JobState::kPaused, "paused"},
    {JobState::kHeld, "held"},
    {JobState::kDone, "done"},
    {JobState::kFailed, "failed"},
    {JobState::kCancelled, "cancelled"},
}};

}  // namespace

std::string_view JobStateName(JobState state) {
  for (const auto& [value, name] : kNames) {
    if (value == state) return name;
  }
  return "unknown";
}

std::optional<JobState> ParseJobState(std::string_view name) {
  for (const auto& [value, known] : kNames) {
    if (known == name) return value;
  }
  return std::nullopt;
}

bool IsTerminal(JobState state) {
  return state == JobState::kDone || state == JobState::kFailed || state == JobState::kCancelled;
}

bool IsAllowedTransition(JobState from, JobState to) {
  using enum JobState;
  switch (from) {
    case kQueued:
      return to == kRunning || to == kPaused || to == kCancelled;
    case kRunning:
      return to == kQueued || to == kPaused || to == kHeld || to == kDone || to == kFailed ||
             to == kCancelled;
    case kPaused:
      return to == kQueued || to == kCancelled;
    case kHeld:
      return to == kQueued || to == kPaused || to == kCancelled;
    case kDone:
    case kFailed:
    case kCancelled:
      return false;
  }
  return false;
}

std::string_view JobCommandName(JobCommand command) {
  switch (command) {
    case JobCommand::kCancel:
      return "cancel";
    case JobCommand::kPause:
      return "pause";
    case JobCommand::kResume:
      return "resume";
  }
  return "unknown";
}

std::string_view JobCommandDone(JobCommand command) {
  switch (command) {
    case JobCommand::kCancel:
      return "cancelled";
    case JobCommand::kPause:
      return "paused";
    case JobCommand::kResume:
      return "resumed";
  }
  return "unknown";
}

JobState CommandTarget(JobCommand command) {
  switch (command) {
    case JobCommand::kCancel:
      return JobState::kCancelled;
    case JobCommand::kPause:
      return JobState::kPaused;
    case JobCommand::kResume:
      return JobState::kQueued;
  }
  return JobState::kQueued;
}

bool IsAllowedCommand(JobState from, JobCommand command) {
  if (command == JobCommand::kResume) return from == JobState::kPaused || from == JobState::kHeld;
  return IsAllowedTransition(from, CommandTarget(command));
}

}  // namespace radfarm::store
