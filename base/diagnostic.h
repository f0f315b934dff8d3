// Formats of the messages the input readers produce, so that every error and warning about a file
// reads "file:line: what" (or "file: what" when no line applies), the way compilers print them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"

namespace radfarm {

// "file:line" or, for line 0, just "file".
std::string Location(std::string_view file, uint32_t line);

// "file:line: what".
Error ErrorAt(std::string_view file, uint32_t line, std::string_view what);

// "file:line: warning: what".
std::string WarningAt(std::string_view file, uint32_t line, std::string_view what);

}  // namespace radfarm
