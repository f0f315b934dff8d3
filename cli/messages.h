// Errors and warnings for a person: one line each on stderr, prefixed with "radfarm: " (a message
// of several lines, such as the files an output could not write, gets the prefix on each).
// Control characters are escaped (cli/printable.h): messages quote scene files, object and
// material names, paths and the master's words, any of which may carry terminal escapes.
#pragma once

#include <string>
#include <vector>

namespace radfarm {

void PrintError(const std::string& message);
void PrintMessages(const std::vector<std::string>& messages);

}  // namespace radfarm
