// A job's timeline: the wall and CPU seconds each phase of a job took and where it ran, so a user
// sees where the time went. `radfarm render` runs every phase itself; on the farm the master
// prepares, folds and plans, the agents trace, and the client writes the outputs (stats.json,
// `radfarm status`, the status page).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace radfarm {

enum class JobPhase : uint8_t {
  kMeshing,      // reading and meshing the scene (and, on the master, packing it for the agents)
  kDirectLight,  // the direct-light start
  kRounds,       // the shooting rounds, refinement steps included
  kGather,       // the final gather
  kDisplay,      // the display's points
  kOutputs,      // the files
};

// "meshing", "direct light", "rounds", "gather", "display", "outputs".
std::string_view JobPhaseName(JobPhase phase);
// The phase of that name, or nullopt.
std::optional<JobPhase> JobPhaseNamed(std::string_view name);
inline constexpr JobPhase kJobPhases[] = {JobPhase::kMeshing, JobPhase::kDirectLight,
                                          JobPhase::kRounds,  JobPhase::kGather,
                                          JobPhase::kDisplay, JobPhase::kOutputs};

// Where a phase ran.
inline constexpr std::string_view kRanHere = "render";
inline constexpr std::string_view kRanOnMaster = "master";
inline constexpr std::string_view kRanOnAgents = "agents";
inline constexpr std::string_view kRanOnClient = "client";

struct TimelineEntry {
  JobPhase phase = JobPhase::kMeshing;
  std::string where;
  // Wall seconds of the phase as `where` saw it (0 where it has no wall of its own: the agents'
  // compute seconds are CPU alone); CPU seconds `where` spent on it.
  double wall_seconds = 0;
  double cpu_seconds = 0;
  bool operator==(const TimelineEntry&) const = default;
};

// Entries in the order phases were first met; one per phase and place.
using JobTimeline = std::vector<TimelineEntry>;

// Adds to the entry of `phase` at `where`, which it appends when there is none yet.
void AddToTimeline(JobTimeline* timeline, JobPhase phase, std::string_view where,
                   double wall_seconds, double cpu_seconds);

// One line for a terminal, per phase its wall seconds (the longest place's) and the CPU seconds of
// each place: "meshing 0.1 s (CPU 0.1 s), gather 6.5 s (CPU: master 0.3 s, agents 12.8 s)".
std::string TimelineLine(const JobTimeline& timeline);

}  // namespace radfarm
