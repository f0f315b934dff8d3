#include "reference/display_error.h"

#include <algorithm>
#include <cmath>

namespace radfarm::reference {

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t rank = size_t(std::ceil(q * double(values.size())));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

ErrorSummary ScoreDisplay(std::vector<PointScore>* scores, double dark_fraction) {
  std::vector<double> refs;
  for (const PointScore& p : *scores) refs.push_back(p.reference.radiance.Sum());
  const double dark_below = dark_fraction * Quantile(refs, 0.5);
  for (PointScore& p : *scores) {
    const double ref = p.reference.radiance.Sum();
    // Dark first: the display has no triangles where the mesher dropped covered ground (under a
    // block), and the light there is nothing.
    p.dark = !(ref > dark_below);
    p.relative_error = !p.dark && p.display ? (p.display->Sum() - ref) / ref : 0;
  }
  return SummarizeScores(*scores);
}

ErrorSummary SummarizeScores(const std::vector<PointScore>& scores, const std::vector<bool>& keep) {
  ErrorSummary s;
  std::vector<double> errors, noise;
  double bias = 0;
  for (size_t i = 0; i < scores.size(); ++i) {
    if (!keep.empty() && !keep[i]) continue;
    const PointScore& p = scores[i];
    ++s.points;
    if (p.dark) {
      ++s.dark;
      continue;
    }
    if (!p.display) {
      ++s.unfound;
      continue;
    }
    const double e = std::abs(p.relative_error);
    errors.push_back(e);
    noise.push_back(p.reference.relative_error);
    bias += p.relative_error;
    if (e > s.worst || s.worst_point < 0) {
      s.worst = e;
      s.worst_point = int64_t(i);
    }
  }
  s.scored = uint32_t(errors.size());
  s.median = Quantile(errors, 0.5);
  s.p95 = Quantile(errors, 0.95);
  s.mean_bias = errors.empty() ? 0 : bias / double(errors.size());
  s.reference_median_error = Quantile(noise, 0.5);
  s.reference_p95_error = Quantile(noise, 0.95);
  return s;
}

}  // namespace radfarm::reference
