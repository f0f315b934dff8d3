// stats.json: every SolveStats field under its own name, then caller-supplied extra numbers and
// strings, as one JSON object. Non-finite numbers are written as null (JSON has no NaN or
// infinity); strings are escaped per RFC 8259, invalid UTF-8 bytes replaced by U+FFFD so the file
// always parses.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"
#include "core/job_timeline.h"
#include "core/solve_stats.h"

namespace radfarm {

using JsonNumbers = std::vector<std::pair<std::string, double>>;
using JsonStrings = std::vector<std::pair<std::string, std::string>>;

// A JSON string literal, quotes included.
std::string JsonString(std::string_view text);

// The document WriteStatsJson writes: the extras, then `timeline` (when not empty) as an array
// "timeline" of {"phase", "where", "wall_seconds", "cpu_seconds"}. Fails when an extra key
// repeats a field or another extra.
Result<std::string> FormatStatsJson(const SolveStats& stats, const JsonNumbers& extra_numbers,
                                    const JsonStrings& extra_strings = {},
                                    const JobTimeline& timeline = {});

// Written atomically; errors name `path`.
Status WriteStatsJson(const std::string& path, const SolveStats& stats,
                      const JsonNumbers& extra_numbers, const JsonStrings& extra_strings = {},
                      const JobTimeline& timeline = {});

}  // namespace radfarm
