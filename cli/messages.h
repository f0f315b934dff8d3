// Errors and warnings for a person: one line each on stderr, prefixed with "radfarm: " (a message
// of several lines, such as the files an output could not write, gets the prefix on each).
#pragma once

#include <string>
#include <vector>

namespace radfarm {

void PrintError(const std::string& message);
void PrintMessages(const std::vector<std::string>& messages);

}  // namespace radfarm
