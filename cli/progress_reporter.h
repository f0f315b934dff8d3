// Progress of a solve for a person watching: a redrawn bar on a terminal, plain log lines (at most
// one a second, plus the last) when stdout is a pipe or a file.
#pragma once

#include <cstdio>

#include "core/solve_control.h"  // ConvergenceFraction, EstimateSecondsLeft
#include "solve/solve_state.h"

namespace radfarm {

class ProgressReporter {
 public:
  // `interactive`: redraw one line in place (a terminal); otherwise print log lines.
  ProgressReporter(std::FILE* out, bool interactive);

  void OnRound(const RoundProgress& progress);
  // Ends the bar's line (interactive) so later output starts on a fresh line.
  void Finish();

 private:
  std::FILE* out_;
  bool interactive_;
  double last_print_seconds_ = -1;
  bool drew_ = false;
};

}  // namespace radfarm
