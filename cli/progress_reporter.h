// Progress of a solve for a person watching: a redrawn bar on a terminal, plain log lines (at most
// one a second, plus the last) when stdout is a pipe or a file. The bar and the ETA count rays:
// the shooting rounds still to come and the final gather (core/progress_estimator.h), so the bar
// does not reach its end before the gather, and the gather shows its own progress.
#pragma once

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include "core/progress_estimator.h"
#include "core/progress_ratchet.h"
#include "display/display_settings.h"
#include "solve/solve_state.h"

namespace radfarm {

class ProgressReporter {
 public:
  // `interactive`: redraw one line in place (a terminal); otherwise print log lines.
  ProgressReporter(std::FILE* out, bool interactive);

  // After each round (the solve's calling thread).
  void OnRound(const RoundProgress& progress);
  // During a round, after each batch (RefiningHooks::during_round: a worker thread, one call at
  // a time). Shows a long round's progress (the final gather, a big scene's first rounds); a
  // round shorter than a redraw (a log line) shows none.
  void OnRoundRunning(const RoundRunning& running);
  // As each step of the display starts (display/display_settings.h): on a terminal the
  // line shows it; a log gets a line for steps of at least kDisplayLogPoints points, the ones
  // that take a while (a count, not a clock, so a log is the same every run).
  void OnDisplayStep(const DisplayStep& step);
  static constexpr uint64_t kDisplayLogPoints = 20000;
  // Ends the bar's line (interactive) so later output starts on a fresh line.
  void Finish();
  // Erases the line drawn last (interactive), for output that replaces it.
  void ClearLine();

 private:
  // "ETA 12s" (the display that follows the solve included: RoundProgress::display_rays), or
  // "ETA ?" before anything is known.
  std::string Eta(const ProgressEstimate& estimate) const;
  void Bar(double fraction, const std::string& text);

  std::FILE* out_;
  bool interactive_;
  std::mutex mutex_;  // OnRound and OnRoundRunning come from different threads
  std::optional<ProgressEstimator> estimator_;  // made at the first round (the tolerance)
  SolvePosition position_;                      // after the last round
  double last_print_seconds_ = -1;
  uint32_t running_round_ = UINT32_MAX;  // the round OnRoundRunning last saw
  double last_running_print_ = -1;       // its round seconds at its last line
  bool drew_ = false;
  ProgressRatchet shown_;  // the bar never goes back when a round refits the estimate
};

}  // namespace radfarm
