// The illuminance report's files in an output directory: illuminance.json (every plane's figures:
// output/illuminance_report.h), and per plane illuminance/<name>.csv (its points) and
// illuminance/<name>.png (output/illuminance_image.h).
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "output/illuminance_report.h"

namespace radfarm {

// Writes nothing for no plane. Each file atomically; every file that can be is written, the error
// holding one line per file that could not be.
Status WriteIlluminanceFiles(const std::string& dir, const std::vector<PlaneIlluminance>& planes);

}  // namespace radfarm
