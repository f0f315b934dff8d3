#include "core/progress_estimator.h"

#include <algorithm>
#include <cmath>

namespace radfarm {
namespace {

// Rounds beyond this are not predicted (a solve that has stopped converging).
constexpr double kMaxRounds = 1e4;
// The time fit has a fixed cost per round only once its rounds' rays span this factor.
constexpr double kOverheadSpread = 10;

// y = slope * x + intercept by least squares, both >= 0: the intercept is dropped (a line
// through the origin, slope sum(y) / sum(x)) when not wanted or when the points cannot fit a
// non-negative one.
struct Line {
  double slope = 0;
  double intercept = 0;
};

Line FitNonNegative(const std::vector<double>& x, const std::vector<double>& y, bool intercept) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double det = n * sxx - sx * sx;
  if (intercept && x.size() >= 2 && det > 1e-12 * n * sxx) {
    const Line line{(n * sxy - sx * sy) / det, (sy * sxx - sx * sxy) / det};
    if (line.slope > 0 && line.intercept >= 0) return line;
  }
  if (sx > 0) return {sy / sx, 0};
  return {0, n > 0 ? sy / n : 0};
}

void Keep(std::vector<RoundSample>& window, const RoundSample& round, size_t size) {
  window.push_back(round);
  if (window.size() > size) window.erase(window.begin());
}

}  // namespace

void ProgressEstimator::AddRound(const RoundSample& round) {
  if (round.seconds > 0) Keep(timed_, round, kTimedWindow);
  if (!round.gather && round.unshot_before > 0) Keep(shooting_, round, kWindow);
}

double ProgressEstimator::ShootingRoundRays(double unshot) const {
  std::vector<double> x, y;
  for (const RoundSample& r : shooting_) {
    x.push_back(r.unshot_before);
    y.push_back(double(r.rays));
  }
  const Line line = FitNonNegative(x, y, true);
  return line.slope * unshot + line.intercept;
}

std::optional<ProgressEstimator::Shooting> ProgressEstimator::ShootingLeft(double unshot) const {
  if (unshot <= tolerance_) return Shooting{};
  if (shooting_.empty()) return std::nullopt;
  // The decay a round, as the geometric mean of the rounds seen.
  double log_decay = 0;
  for (const RoundSample& r : shooting_) {
    log_decay += std::log(std::max(r.unshot_after, 1e-300) / r.unshot_before);
  }
  log_decay /= double(shooting_.size());
  const double q = std::exp(std::min(log_decay, std::log(0.999)));
  const double rounds =
      std::min(kMaxRounds, std::ceil(std::log(tolerance_ / unshot) / std::log(q)));
  // Sum over the rounds j = 0 .. rounds-1 of a * unshot * q^j + b.
  const double a_part = ShootingRoundRays(unshot) - ShootingRoundRays(0);
  const double b = ShootingRoundRays(0);
  return Shooting{rounds, a_part * (1 - std::pow(q, rounds)) / (1 - q) + b * rounds};
}

std::optional<double> ProgressEstimator::Seconds(double rays, double rounds) const {
  if (timed_.empty()) return std::nullopt;
  std::vector<double> x, y;
  double fewest = INFINITY, most = 0;
  for (const RoundSample& r : timed_) {
    x.push_back(double(r.rays));
    y.push_back(r.seconds);
    fewest = std::min(fewest, x.back());
    most = std::max(most, x.back());
  }
  // A round's fixed cost shows only beside rounds of far fewer rays. Between big rounds alone, a
  // ray's cost differs from round to round (other shooters), and a line through two of them can
  // put a round's fixed cost at hundreds of times a real one (a few ms) and the ETA far too high.
  // Until then, seconds are in proportion to the rays.
  const Line line = FitNonNegative(x, y, /*intercept=*/most >= kOverheadSpread * fewest);
  return line.slope * rays + line.intercept * rounds;
}

namespace {

// `e` cut to what the budget leaves (SolvePosition::budget_*): the rays and seconds still to come
// scaled down together to the first the budget runs out of; `done` the rays done.
ProgressEstimate WithinBudget(ProgressEstimate e, const SolvePosition& now, double done) {
  const double rays_left = double(e.rays_left);
  double scale = 1;
  if (now.budget_rays_left && rays_left > 0) {
    scale = std::min(scale, double(*now.budget_rays_left) / rays_left);
  }
  if (now.budget_seconds_left && e.seconds_left && *e.seconds_left > 0) {
    scale = std::min(scale, std::max(0.0, *now.budget_seconds_left) / *e.seconds_left);
  }
  if (!(scale < 1)) return e;
  e.rays_left = uint64_t(std::llround(rays_left * scale));
  e.fraction = done + rays_left * scale > 0 ? done / (done + rays_left * scale) : 1;
  if (e.seconds_left) *e.seconds_left *= scale;
  return e;
}

}  // namespace

ProgressEstimate ProgressEstimator::Estimate(const SolvePosition& now) const {
  ProgressEstimate out = SolveEstimate(now);
  if (now.display_rays == 0 || !out.seconds_left) return out;
  // The display's rays are traced as one pass over its points: no round's fixed cost.
  if (std::optional<double> display = Seconds(double(now.display_rays) * gather_ray_cost_, 0)) {
    *out.seconds_left += *display;
  }
  return out;
}

ProgressEstimate ProgressEstimator::SolveEstimate(const SolvePosition& now) const {
  ProgressEstimate out;
  const bool running = now.round_rays > 0;
  const double round_rest = double(now.round_rays - std::min(now.round_rays, now.round_rays_done));
  // What comes after the running round (or from now, between rounds).
  std::optional<Shooting> shooting;
  double gather_rays = double(now.gather_rays_left);
  double gather_rounds = now.gather_rays_left > 0 ? 1 : 0;
  if (running && now.round_gather) {
    shooting = Shooting{};
    gather_rays = gather_rounds = 0;  // the running round is the gather
  } else {
    shooting = ShootingLeft(now.unshot_fraction);
    if (shooting && running && shooting->rounds > 0) {
      // The running round is the first of them.
      shooting->rays = std::max(0.0, shooting->rays - ShootingRoundRays(now.unshot_fraction));
      shooting->rounds -= 1;
    }
  }
  const double later_rays = (shooting ? shooting->rays : 0) + gather_rays;
  const double rays_left = round_rest + later_rays;
  out.rays_left = uint64_t(std::llround(rays_left));
  const double done = double(now.rays_done + std::min(now.round_rays, now.round_rays_done));
  if (!shooting) {
    // The shooting still to come cannot be sized yet (no shooting round seen): the rays known
    // so far (the first round, the gather) are only part of the rest, and a fraction of them
    // climbed high in the first round, then fell when the second showed the rounds to come. So
    // the fraction is the one the budget bounds it by, or 0: it only rises from there.
    if (now.budget_rays_left) {
      const double most = done + double(*now.budget_rays_left);
      out.fraction = most > 0 ? done / most : 0;
    }
    return out;
  }
  out.fraction = done + rays_left > 0 ? done / (done + rays_left) : 0;

  const double later_cost = (shooting ? shooting->rays : 0) + gather_rays * gather_ray_cost_;
  std::optional<double> later = Seconds(later_cost, shooting->rounds + gather_rounds);
  if (!later) return WithinBudget(out, now, done);
  double rest = 0;
  if (running) {
    // The running round at the fitted pace, trusting its own pace more as it goes: its first
    // tenth runs while threads start and caches fill, and looks slower than the rest.
    const double cost = double(now.round_rays) * (now.round_gather ? gather_ray_cost_ : 1.0);
    rest = std::max(0.0, *Seconds(cost, 1) - now.round_seconds);
    if (now.round_rays_done > 0 && now.round_seconds > 0) {
      const double own = now.round_seconds * round_rest / double(now.round_rays_done);
      const double done = double(std::min(now.round_rays, now.round_rays_done)) / now.round_rays;
      rest = done * own + (1 - done) * rest;
    }
  }
  out.seconds_left = rest + *later;
  return WithinBudget(out, now, done);
}

}  // namespace radfarm
