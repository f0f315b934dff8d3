#include "core/job_timeline.h"

#include <algorithm>
#include <cstdio>

namespace radfarm {

std::string_view JobPhaseName(JobPhase phase) {
  switch (phase) {
    case JobPhase::kMeshing:
      return "meshing";
    case JobPhase::kDirectLight:
      return "direct light";
    case JobPhase::kRounds:
      return "rounds";
    case JobPhase::kGather:
      return "gather";
    case JobPhase::kDisplay:
      return "display";
    case JobPhase::kOutputs:
      return "outputs";
  }
  return "?";
}

std::optional<JobPhase> JobPhaseNamed(std::string_view name) {
  for (JobPhase phase : kJobPhases) {
    if (JobPhaseName(phase) == name) return phase;
  }
  return std::nullopt;
}

void AddToTimeline(JobTimeline* timeline, JobPhase phase, std::string_view where,
                   double wall_seconds, double cpu_seconds) {
  for (TimelineEntry& e : *timeline) {
    if (e.phase == phase && e.where == where) {
      e.wall_seconds += wall_seconds;
      e.cpu_seconds += cpu_seconds;
      return;
    }
  }
  timeline->push_back({phase, std::string(where), wall_seconds, cpu_seconds});
}

std::string TimelineLine(const JobTimeline& timeline) {
  std::vector<JobPhase> phases;
  for (const TimelineEntry& e : timeline) {
    if (std::find(phases.begin(), phases.end(), e.phase) == phases.end()) phases.push_back(e.phase);
  }
  std::string line;
  char text[64];
  for (JobPhase phase : phases) {
    double wall = 0;
    std::string cpu;
    const auto places = std::count_if(timeline.begin(), timeline.end(),
                                      [&](const TimelineEntry& e) { return e.phase == phase; });
    for (const TimelineEntry& e : timeline) {
      if (e.phase != phase) continue;
      wall = std::max(wall, e.wall_seconds);
      if (places == 1) {
        std::snprintf(text, sizeof text, "%.1f s", e.cpu_seconds);
      } else {
        std::snprintf(text, sizeof text, "%s%s %.1f s", cpu.empty() ? ": " : ", ", e.where.c_str(),
                      e.cpu_seconds);
      }
      cpu += text;
    }
    std::snprintf(text, sizeof text, "%.1f s", wall);
    line += (line.empty() ? "" : ", ") + std::string(JobPhaseName(phase)) + " " + text + " (CPU" +
            (places == 1 ? " " : "") + cpu + ")";
  }
  return line;
}

}  // namespace radfarm
