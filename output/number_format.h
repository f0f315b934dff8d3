// Text form of numbers for the CSV and JSON writers: the shortest decimal that parses back to the
// same double, independent of locale, so equal results give byte-identical files.
#pragma once

#include <cstdint>
#include <string>

namespace radfarm {

// Shortest round-trip form ("0.1", "1e+300", "inf", "nan"); strtod reads it back exactly.
std::string FormatDouble(double value);
std::string FormatUnsigned(uint64_t value);

}  // namespace radfarm
