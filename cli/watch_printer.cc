#include "cli/watch_printer.h"

#include <algorithm>

#include "cli/farm_format.h"

namespace radfarm {

std::string FormatWatchLine(const JobInfo& j) {
  char text[256];
  std::snprintf(text, sizeof text, "job %lld %s: round %llu, unshot %.4f%%, %llu rays, %s, %llu %s",
                static_cast<long long>(j.id), j.state.c_str(),
                static_cast<unsigned long long>(j.round), 100 * j.unshot_fraction,
                static_cast<unsigned long long>(j.rays),
                FormatRaysPerSecond(j.rays_per_second).c_str(),
                static_cast<unsigned long long>(j.agents), j.agents == 1 ? "agent" : "agents");
  std::string line = text;
  if (!IsTerminalState(j.state)) {
    line += ", ETA " + (j.eta_seconds ? FormatDuration(*j.eta_seconds) : std::string("?"));
    char done[32];
    std::snprintf(done, sizeof done, ", %.0f%% done", 100 * std::clamp(j.progress, 0.0, 1.0));
    line += done;
  }
  // Its rounds are over but its display is not drawn yet: on a big scene that takes a while.
  if (j.phase == "display") line += ", drawing the display";
  if (j.waiting_for_agents) line += std::string("; ") + kNoAgentConnected;
  if (j.stop_reason) line += ", " + *j.stop_reason;
  if (j.error) line += ": " + *j.error;
  return line;
}

WatchPrinter::WatchPrinter(std::FILE* out, WatchStyle style) : out_(out), style_(style) {}

void WatchPrinter::Show(const JobInfo& job, const nlohmann::json& object) {
  if (style_ == WatchStyle::kBar) {
    constexpr int kWidth = 30;
    const int filled = int(std::clamp(job.progress, 0.0, 1.0) * kWidth);
    // \r returns to the line's start; ESC [K clears what a longer previous line left behind.
    std::fprintf(out_, "\r[%s%s] %s\x1b[K", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), FormatWatchLine(job).c_str());
    drew_bar_ = true;
  } else {
    const Seen seen{job.state,
                    job.round,
                    job.agents,
                    job.waiting_for_agents,
                    int(std::clamp(job.progress, 0.0, 1.0) * 10),
                    job.phase == "display"};
    if (last_ == seen) return;
    last_ = seen;
    const std::string line =
        style_ == WatchStyle::kJsonLines ? object.dump() : FormatWatchLine(job);
    std::fprintf(out_, "%s\n", line.c_str());
  }
  std::fflush(out_);
}

void WatchPrinter::Finish() {
  if (drew_bar_) std::fputc('\n', out_);
  drew_bar_ = false;
  std::fflush(out_);
}

}  // namespace radfarm
