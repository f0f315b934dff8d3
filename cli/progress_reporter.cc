#include "cli/progress_reporter.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace radfarm {
namespace {

constexpr int kBarWidth = 30;
// A terminal's bar is redrawn at most this often during a round; a log gets a line at most once
// a second.
constexpr double kRedrawSeconds = 0.2;
constexpr double kLogLineSeconds = 1.0;

}  // namespace

ProgressReporter::ProgressReporter(std::FILE* out, bool interactive)
    : out_(out), interactive_(interactive) {}

std::string ProgressReporter::Eta(const ProgressEstimate& e) const {
  if (!e.seconds_left) return "ETA ?";
  return "ETA " + std::to_string(int64_t(std::ceil(*e.seconds_left))) + "s";
}

void ProgressReporter::Bar(double fraction, const std::string& text) {
  const int filled = int(shown_.Show(fraction) * kBarWidth);
  std::fprintf(out_, "\r[%s%s] %s   ", std::string(filled, '#').c_str(),
               std::string(kBarWidth - filled, '.').c_str(), text.c_str());
  drew_ = true;
}

void ProgressReporter::OnDisplayStep(const DisplayStep& step) {
  std::lock_guard lock(mutex_);
  const std::string points = std::to_string(step.points);
  std::string text;
  switch (step.kind) {
    case DisplayStep::kDirectLight:
      text = "display: direct light at " + points + " points";
      break;
    case DisplayStep::kGathering:
      text = "display: gathering light at " + points + " points near other surfaces";
      break;
    case DisplayStep::kRefining:
      text = "display: " + points + " points added where the light bends (level " +
             std::to_string(step.level) + " of " + std::to_string(kDisplayRefineLevels) + ")";
      break;
  }
  if (interactive_) {
    std::fprintf(out_, "\r\033[K%s", text.c_str());
    drew_ = true;
  } else if (step.points >= kDisplayLogPoints) {
    std::fprintf(out_, "%s\n", text.c_str());
  }
  std::fflush(out_);
}

void ProgressReporter::OnRound(const RoundProgress& p) {
  std::lock_guard lock(mutex_);
  if (!estimator_) estimator_.emplace(p.tolerance);
  estimator_->SetGatherRayCost(p.gather_ray_cost);
  estimator_->AddRound(
      {p.round_rays, p.round_seconds, p.unshot_before, p.unshot_fraction, p.gather});
  position_ = {p.rays, p.unshot_fraction, p.gather_rays_left};
  position_.budget_rays_left = p.budget_rays_left;
  position_.budget_seconds_left = p.budget_seconds_left;
  position_.display_rays = p.display_rays;
  const ProgressEstimate e = estimator_->Estimate(position_);
  const double rate = p.seconds > 0 ? double(p.rays) / p.seconds : 0;
  char text[160];
  if (p.gather) {
    std::fprintf(out_, "%sfinal gather: %llu rays in all, %.2f Mrays/s\n", drew_ ? "\n" : "",
                 static_cast<unsigned long long>(p.rays), rate / 1e6);
    drew_ = false;
  } else if (interactive_) {
    std::snprintf(text, sizeof text, "round %u  unshot %.3f%%  %.2f Mrays/s  %s", p.round,
                  100 * p.unshot_fraction, rate / 1e6, Eta(e).c_str());
    Bar(e.fraction, text);
  } else {
    const bool last = p.unshot_fraction <= p.tolerance;
    if (!last && p.seconds - last_print_seconds_ < kLogLineSeconds) return;
    last_print_seconds_ = p.seconds;
    std::fprintf(out_, "round %u: unshot %.4f%% of emitted, %llu rays, %.2f Mrays/s, %s\n", p.round,
                 100 * p.unshot_fraction, static_cast<unsigned long long>(p.rays), rate / 1e6,
                 Eta(e).c_str());
  }
  std::fflush(out_);
}

void ProgressReporter::OnRoundRunning(const RoundRunning& r) {
  if (r.round_rays == 0) return;
  std::lock_guard lock(mutex_);
  if (r.round != running_round_) {
    running_round_ = r.round;
    last_running_print_ = -1;
  }
  const double every = interactive_ ? kRedrawSeconds : kLogLineSeconds;
  const bool last = r.round_rays_done >= r.round_rays;
  if (last || (last_running_print_ >= 0 && r.round_seconds - last_running_print_ < every)) return;
  if (last_running_print_ < 0 && r.round_seconds < every) return;  // a short round needs no lines
  last_running_print_ = r.round_seconds;
  SolvePosition now = position_;
  now.round_rays = r.round_rays;
  now.round_rays_done = r.round_rays_done;
  now.round_seconds = r.round_seconds;
  now.round_gather = r.gather;
  if (now.budget_rays_left) {
    now.budget_rays_left =
        *now.budget_rays_left - std::min(*now.budget_rays_left, r.round_rays_done);
  }
  now.budget_seconds_left = r.budget_seconds_left;
  // Before the first round ends there is no estimator: no ETA yet.
  const ProgressEstimate e = estimator_ ? estimator_->Estimate(now) : ProgressEstimate{};
  const double part = double(r.round_rays_done) / double(r.round_rays);
  const double rate = r.round_seconds > 0 ? double(r.round_rays_done) / r.round_seconds : 0;
  const std::string what = r.gather ? "final gather" : "round " + std::to_string(r.round + 1);
  char text[160];
  std::snprintf(text, sizeof text, "%s %.0f%% of %llu rays  %.2f Mrays/s  %s", what.c_str(),
                100 * part, static_cast<unsigned long long>(r.round_rays), rate / 1e6,
                Eta(e).c_str());
  if (interactive_) {
    Bar(e.fraction, text);
  } else {
    std::fprintf(out_, "%s\n", text);
  }
  std::fflush(out_);
}

void ProgressReporter::ClearLine() {
  std::lock_guard lock(mutex_);
  if (interactive_ && drew_) std::fputs("\r\033[K", out_);
  drew_ = false;
  std::fflush(out_);
}

void ProgressReporter::Finish() {
  std::lock_guard lock(mutex_);
  if (interactive_ && drew_) std::fputc('\n', out_);
  drew_ = false;
  std::fflush(out_);
}

}  // namespace radfarm
