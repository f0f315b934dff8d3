#include "cli/farm_format.h"

#include <time.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace radfarm {
namespace {

std::string Printf(const char* format, auto... args) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, format, args...);
  return buffer;
}

std::string Percent(double fraction, const char* format) { return Printf(format, 100 * fraction); }

std::string Eta(const JobInfo& job) {
  if (IsTerminalState(job.state)) return "-";
  return job.eta_seconds ? FormatDuration(*job.eta_seconds) : "?";
}

std::string OptionalTime(const std::optional<int64_t>& ms) { return ms ? FormatUtcTime(*ms) : "-"; }

}  // namespace

std::string FormatUtcTime(int64_t unix_ms, bool with_ms) {
  const time_t seconds = time_t(unix_ms / 1000 - (unix_ms % 1000 < 0 ? 1 : 0));
  const int64_t ms = unix_ms - int64_t(seconds) * 1000;
  tm utc{};
  if (gmtime_r(&seconds, &utc) == nullptr) return std::to_string(unix_ms) + " ms";
  char text[64];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &utc);
  return std::string(text) + (with_ms ? Printf(".%03" PRId64, ms) : "") + " UTC";
}

std::string FormatDuration(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  const int64_t s = int64_t(std::ceil(seconds));
  if (s < 60) return Printf("%" PRId64 "s", s);
  if (s < 3600) return Printf("%" PRId64 "m%02" PRId64 "s", s / 60, s % 60);
  return Printf("%" PRId64 "h%02" PRId64 "m", s / 3600, s / 60 % 60);
}

std::string FormatRaysPerSecond(double rays_per_second) {
  return Printf("%.2f Mrays/s", rays_per_second / 1e6);
}

std::string FormatTable(const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> widths;
  for (const auto& row : rows) {
    widths.resize(std::max(widths.size(), row.size()));
    for (size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  }
  std::string text;
  for (const auto& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(widths[c] - row[c].size() + 2, ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    text += line + "\n";
  }
  return text;
}

std::string FormatJobTable(const std::vector<JobInfo>& jobs) {
  std::vector<std::vector<std::string>> rows = {{"ID", "NAME", "STATE", "PRIORITY", "ROUND",
                                                 "UNSHOT", "PROGRESS", "RAYS/S", "AGENTS", "ETA"}};
  for (const JobInfo& j : jobs) {
    rows.push_back({std::to_string(j.id), j.name, j.state, std::to_string(j.priority),
                    std::to_string(j.round), Percent(j.unshot_fraction, "%.4f%%"),
                    Percent(j.progress, "%.0f%%"), FormatRaysPerSecond(j.rays_per_second),
                    std::to_string(j.agents), Eta(j)});
  }
  return FormatTable(rows);
}

std::string FormatJobStatus(const JobInfo& j) {
  std::vector<std::vector<std::string>> rows = {
      {"job:", std::to_string(j.id)},
      {"name:", j.name},
      {"state:", j.state + (j.phase ? " (" + *j.phase + ")" : std::string())},
      {"priority:", std::to_string(j.priority)},
      {"round:", std::to_string(j.round)},
      {"unshot:", Percent(j.unshot_fraction, "%.4f%%") + " of emitted (tolerance " +
                      Percent(j.tolerance, "%.4f%%") + ")"},
      {"progress:", Percent(j.progress, "%.1f%%")},
      {"rays:", std::to_string(j.rays)},
      {"rays/s:", FormatRaysPerSecond(j.rays_per_second)},
      {"agents:", std::to_string(j.agents) +
                      (j.waiting_for_agents ? std::string(", ") + kNoAgentConnected : "")},
      {"ETA:", Eta(j)},
      {"patches:", std::to_string(j.patches)},
      {"seed:", std::to_string(j.seed)},
      {"scene:", j.scene_hash},
      {"submitted:", OptionalTime(j.submitted_at_ms)},
      {"started:", OptionalTime(j.started_at_ms)},
      {"finished:", OptionalTime(j.finished_at_ms)}};
  if (j.stop_reason) rows.push_back({"stopped:", *j.stop_reason});
  if (j.direct_start) rows.push_back({"direct light:", *j.direct_start});
  if (j.display) rows.push_back({"display:", *j.display});
  if (!j.timeline.empty()) rows.push_back({"time:", TimelineLine(j.timeline)});
  // A held or paused job is not broken: its text is why it waits.
  const bool waiting = j.state == "held" || j.state == "paused";
  if (j.error) rows.push_back({waiting ? "reason:" : "error:", *j.error});
  return FormatTable(rows);
}

std::string FormatAgentTable(const std::vector<AgentInfo>& agents) {
  std::vector<std::vector<std::string>> rows = {{"ID", "NAME", "ADDRESS", "THREADS", "RAYS/S",
                                                 "LOAD", "LEASES", "RESULTS", "HEARTBEAT",
                                                 "CONNECTED"}};
  for (const AgentInfo& a : agents) {
    rows.push_back({std::to_string(a.id), a.name, a.address, std::to_string(a.threads),
                    FormatRaysPerSecond(a.rays_per_second), Printf("%.2f", a.load),
                    std::to_string(a.leases), std::to_string(a.results),
                    FormatDuration(a.last_heartbeat_ms_ago / 1000.0) + " ago",
                    FormatUtcTime(a.connected_ms)});
  }
  return FormatTable(rows);
}

std::string FormatEvent(const EventInfo& e) {
  return FormatUtcTime(e.time_ms, /*with_ms=*/true) + "  " + e.level +
         std::string(e.level.size() < 7 ? 7 - e.level.size() : 0, ' ') + "  " +
         (e.job ? "job " + std::to_string(*e.job) + ": " : std::string()) + e.text;
}

}  // namespace radfarm
