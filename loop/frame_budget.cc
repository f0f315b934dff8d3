#include "loop/frame_budget.h"

#include <algorithm>

#include "loop/check.h"

namespace radfarm::loop {

bool FrameBudget::Take(uint64_t bytes) {
  if (bytes > limit_ - held_) {
    ++refused_;
    return false;
  }
  held_ += bytes;
  peak_ = std::max(peak_, held_);
  return true;
}

void FrameBudget::Give(uint64_t bytes) {
  LOOP_CHECK(bytes <= held_);
  held_ -= bytes;
}

}  // namespace radfarm::loop
