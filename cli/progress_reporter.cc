#include "cli/progress_reporter.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace radfarm {

ProgressReporter::ProgressReporter(std::FILE* out, bool interactive)
    : out_(out), interactive_(interactive) {}

void ProgressReporter::OnRound(const RoundProgress& p) {
  const double rate = p.seconds > 0 ? double(p.rays) / p.seconds : 0;
  const double eta =
      EstimateSecondsLeft(p.unshot_fraction, p.tolerance, p.seconds, p.rays, p.gather_rays_left);
  const std::string eta_text = eta < 0 ? "?" : std::to_string(int(std::ceil(eta))) + "s";
  if (p.gather) {
    std::fprintf(out_, "%sfinal gather: %llu rays in all, %.2f Mrays/s\n", drew_ ? "\n" : "",
                 static_cast<unsigned long long>(p.rays), rate / 1e6);
    drew_ = false;
  } else if (interactive_) {
    constexpr int kWidth = 30;
    const int filled = int(ConvergenceFraction(p.unshot_fraction, p.tolerance) * kWidth);
    std::fprintf(out_, "\r[%s%s] round %u  unshot %.3f%%  %.2f Mrays/s  ETA %s   ",
                 std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(),
                 p.round, 100 * p.unshot_fraction, rate / 1e6, eta_text.c_str());
    drew_ = true;
  } else {
    const bool last = p.unshot_fraction <= p.tolerance;
    if (!last && p.seconds - last_print_seconds_ < 1.0) return;
    last_print_seconds_ = p.seconds;
    std::fprintf(out_, "round %u: unshot %.4f%% of emitted, %llu rays, %.2f Mrays/s, ETA %s\n",
                 p.round, 100 * p.unshot_fraction, static_cast<unsigned long long>(p.rays),
                 rate / 1e6, eta_text.c_str());
  }
  std::fflush(out_);
}

void ProgressReporter::Finish() {
  if (interactive_ && drew_) std::fputc('\n', out_);
  std::fflush(out_);
}

}  // namespace radfarm
