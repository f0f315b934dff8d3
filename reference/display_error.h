// The display's error against the reference at scored points: relative error of the channel sum,
// (display - reference) / reference, and its summary. Points darker than `dark_fraction` of the
// median reference (behind a lamp, under a block) have no meaningful relative error: they are
// counted, not scored.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/rgb.h"
#include "reference/path_tracer.h"

namespace radfarm::reference {

struct PointScore {
  SurfacePoint point;
  PointEstimate reference;
  std::optional<Rgb> display;  // nothing when no display triangle was found there
  double relative_error = 0;   // signed; 0 for dark or unfound points
  bool dark = false;
};

struct ErrorSummary {
  uint32_t points = 0;
  uint32_t scored = 0;
  uint32_t dark = 0;
  uint32_t unfound = 0;  // not dark, but no display triangle there
  double median = 0;     // of |relative error|
  double p95 = 0;
  double worst = 0;
  int64_t worst_point = -1;  // index into the scores
  double mean_bias = 0;      // mean signed relative error
  // The reference's own: median and p95 relative standard error over the scored points.
  double reference_median_error = 0;
  double reference_p95_error = 0;
};

inline constexpr double kDarkFraction = 0.01;

// Fills each score's relative_error and dark flag, and summarises.
ErrorSummary ScoreDisplay(std::vector<PointScore>* scores, double dark_fraction = kDarkFraction);

// The summary of the scores `keep` selects (all of them when it is empty), as ScoreDisplay left
// them: a subset is judged dark by the whole set's median. worst_point indexes `scores`.
ErrorSummary SummarizeScores(const std::vector<PointScore>& scores,
                             const std::vector<bool>& keep = {});

// The q-quantile (0..1) of `values` by the nearest-rank rule; 0 when empty.
double Quantile(std::vector<double> values, double q);

}  // namespace radfarm::reference
