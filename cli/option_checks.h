// Checks of numeric command-line values with messages a person can read (CLI11's own range checks
// print the whole range of a double: "not in range 0.000000 to 1797693134862315...").
#pragma once

#include <CLI/CLI.hpp>

#include "base/toml_table_reader.h"

namespace radfarm {

// An integer >= 1 that fits in int64 (job ids, counts).
const CLI::Validator& PositiveInteger();
// An integer from 0 to 2^64 - 1 in decimal digits (seeds): "-1" or 2^64 are refused, not wrapped
// or clamped.
const CLI::Validator& UnsignedInteger();
// A size in bytes from 1 to 2^64 - 1: digits with an optional unit of 1024s (K, M, G, T; "KB" and
// "KiB" alike, any case); turns the text into the number of bytes. "-1" and overflows are refused.
const CLI::Validator& ByteSize();
// A job id: decimal digits, 1 to 2^64 - 1.
const CLI::Validator& PositiveId();
// A finite number > 0 (seconds, lengths).
const CLI::Validator& PositiveReal();
// A number in [low, high].
CLI::Validator RealInRange(double low, double high);
// A number in `range`, refused in the job file's words: "must be in (0, 1), got 1".
CLI::Validator RealIn(const Interval& range);

}  // namespace radfarm
