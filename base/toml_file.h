// Reads a TOML file (job files, the daemons' config files) into a toml++ table; syntax errors read
// "file:line: what", like every other input error.
#pragma once

#include <toml++/toml.h>

#include <string>

#include "base/result.h"

namespace radfarm {

Result<toml::table> ParseToml(const std::string& path, const std::string& text);
Result<toml::table> ReadTomlFile(const std::string& path);

}  // namespace radfarm
