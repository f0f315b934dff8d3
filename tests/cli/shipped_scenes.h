// The shipped scenes/ as the render tests walk them: an OBJ that a shipped job hangs IES lamps in,
// or lights by a sky, emits nothing of its own, so it renders only through its job.
#pragma once

#include <filesystem>
#include <set>
#include <string>

namespace radfarm::testing {

// The canonical paths of the scenes the job files in `dir` hang lamps in or light by a sky.
std::set<std::filesystem::path> ScenesLitByJobLamps(const std::string& dir);

}  // namespace radfarm::testing
