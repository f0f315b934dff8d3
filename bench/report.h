// Writes docs/BENCHMARKS.md from a BenchReport.
#pragma once

#include <string>

#include "bench/bench_report.h"

namespace radfarm::bench {

std::string RenderReport(const BenchReport& report);

// Writes the report to `path` (through a temporary file, renamed into place). Returns an empty
// string on success, else what went wrong.
std::string WriteReport(const BenchReport& report, const std::string& path);

}  // namespace radfarm::bench
