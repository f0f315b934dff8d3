#include "farmsim/delay_line.h"

#include <chrono>
#include <cmath>

namespace radfarm::sim {
namespace {

// Items this close to due run now rather than costing another timer round.
constexpr double kEarlySeconds = 100e-6;

}  // namespace

double SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

DelayLine::DelayLine(loop::EventLoop& loop) : timer_(std::make_unique<loop::Timer>(loop)) {}

void DelayLine::At(double due, std::function<void()> fn) {
  items_.push({due, next_seq_++, std::move(fn)});
  if (armed_for_ < 0 || due < armed_for_) Arm();
}

void DelayLine::Close() {
  if (timer_) timer_->Close();
  timer_.reset();
  items_ = {};
}

void DelayLine::Arm() {
  if (!timer_ || items_.empty()) {
    armed_for_ = -1;
    return;
  }
  const double due = items_.top().due;
  const double wait = std::max(0.0, due - SteadySeconds());
  armed_for_ = due;
  timer_->Start(std::chrono::milliseconds(static_cast<int64_t>(std::ceil(wait * 1000))),
                [this] { Fire(); });
}

void DelayLine::Fire() {
  armed_for_ = -1;
  while (!items_.empty() && timer_) {
    const double now = SteadySeconds();
    if (items_.top().due > now + kEarlySeconds) break;
    Item item = std::move(const_cast<Item&>(items_.top()));
    items_.pop();
    const double late = std::max(0.0, now - item.due);
    ++fired_;
    lateness_sum_ += late;
    lateness_max_ = std::max(lateness_max_, late);
    item.fn();
  }
  if (armed_for_ < 0) Arm();
}

}  // namespace radfarm::sim
