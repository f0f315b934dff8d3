// ProgressRatchet: the progress a person is shown, which never goes back. An estimate
// (core/progress_estimator.h) falls when a round refits its model and more rounds are left than
// the last fit said; shown as it is, a bar would step back. The ratchet shows the highest estimate
// seen instead, and the bar waits there for the estimate to catch up.
//
// Not thread-safe: one owner (render's reporter, the master's loop thread).
#pragma once

#include <algorithm>

namespace radfarm {

class ProgressRatchet {
 public:
  // The fraction to show for `estimate` (clamped to 0..1): never below one shown before.
  double Show(double estimate) {
    shown_ = std::max(shown_, std::clamp(estimate, 0.0, 1.0));
    return shown_;
  }
  double shown() const { return shown_; }

 private:
  double shown_ = 0;
};

}  // namespace radfarm
