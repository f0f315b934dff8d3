// Writes docs/BENCHMARKS-adaptive.md and its PNG plots from the studies of every scene, with the
// issue's aims checked against the rows and the defaults argued from them.
#pragma once

#include <string>
#include <vector>

#include "bench/refine/study.h"

namespace radfarm::bench {

struct ReportRun {
  std::string out_dir;
  bool quick = false;
  double total_seconds = 0;
  std::string machine;           // one line: CPUs, load
  bool reference_cache = false;  // references read back from --reference-cache when there
};

void WriteAdaptiveReport(const ReportRun& run, const std::vector<StudyResult>& studies);

}  // namespace radfarm::bench
