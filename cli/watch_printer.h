// WatchPrinter: what `radfarm status ID --watch` shows of a job it polls. On a terminal, one line
// redrawn in place: a progress bar with round, unshot power, rays/s, agents and ETA. Otherwise (a
// pipe, a file, or --json) one line per change of state, round, agent count or tenth of progress:
// a log to read later, not a copy of every poll.
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/control_objects.h"

namespace radfarm {

enum class WatchStyle {
  kBar,        // a terminal: redraw one line
  kLines,      // one text line per change
  kJsonLines,  // one compact job object per line per change
};

// "job 3 running: round 12, unshot 0.5320%, 123456 rays, 3.21 Mrays/s, 2 agents, ETA 14s", then
// kNoAgentConnected when the job waits for agents and none is connected, the stop reason or the
// error when there is one.
std::string FormatWatchLine(const JobInfo& job);

class WatchPrinter {
 public:
  WatchPrinter(std::FILE* out, WatchStyle style);

  // `object` is the master's JSON for `job` (printed in kJsonLines style).
  void Show(const JobInfo& job, const nlohmann::json& object);
  // Ends the bar's line so later output starts on a fresh line.
  void Finish();

 private:
  struct Seen {
    std::string state;
    uint64_t round;
    uint64_t agents;
    bool waiting_for_agents;
    int tenths;    // of progress: a long round (the final gather) still shows it moving
    bool display;  // its display being drawn: the line says so
    bool operator==(const Seen&) const = default;
  };

  std::FILE* out_;
  WatchStyle style_;
  std::optional<Seen> last_;
  bool drew_bar_ = false;
};

}  // namespace radfarm
