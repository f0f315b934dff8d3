// Turns the measured numbers into the report's conclusions, so the text never disagrees with the
// tables it sits under.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bench/bench_report.h"
#include "core/solver_settings.h"

namespace radfarm::bench {

// Which of SweepPoint's two error measures to judge by.
using ErrorMeasure = double SweepPoint::*;

// The samplers compared on one scene at one wall time that every sampler's line reaches.
struct SceneVerdict {
  std::string scene;
  bool common_time = false;  // false: the lines do not overlap in time; judged by error² × time
  double seconds = 0;        // the common time
  std::vector<std::pair<SamplerKind, double>> scores;  // per sampler: error at that time (or e² t)
  SamplerKind best = SamplerKind::kSobol;
  std::vector<SamplerKind> leaders;  // best and those within kTieRatio of it
};

// Scores within this factor of the best count as a tie: one seed per point and a shared machine
// make smaller differences noise.
inline constexpr double kTieRatio = 1.15;

// Error of one sampler's line at `seconds`, interpolated linearly in log-log between the nearest
// points; negative when `seconds` is outside the line's time range.
double ErrorAtTime(const SceneSweep& sweep, SamplerKind sampler, ErrorMeasure measure,
                   double seconds);

SceneVerdict JudgeScene(const SceneSweep& sweep, ErrorMeasure measure);

// Paragraphs of Markdown.
std::vector<std::string> Conclusions(const BenchReport& report);

}  // namespace radfarm::bench
