// The numbers of an illuminance report: per plane (and per level of it: one storey's floors, say)
// the count, minimum, mean and maximum of the lux at its grid points and the uniformities
// EN 12464-1 asks for, U0 = min / mean and Ud = min / max; the points as CSV and the whole as
// JSON. Numbers are written shortest-round-trip (output/number_format.h): the same lux, the same
// bytes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "base/result.h"
#include "output/illuminance_grid.h"
#include "output/illuminance_plane.h"

namespace radfarm {

struct LuxSummary {
  size_t points = 0;
  double min = 0, mean = 0, max = 0;
  double uniformity = 0;  // U0 = min / mean; 0 where the mean is 0 or there is no point
  double diversity = 0;   // Ud = min / max; 0 likewise
};

LuxSummary SummariseLux(const std::vector<double>& lux);

// A plane's grid and the lux at its points (one per grid point).
struct PlaneIlluminance {
  IlluminancePlane plane;
  IlluminanceGrid grid;
  std::vector<double> lux;
};

// "x,y,z,lux" and one line per point, in the grid's order; lines end in "\n".
inline constexpr char kIlluminanceCsvHeader[] = "x,y,z,lux";
std::string IlluminanceCsv(const PlaneIlluminance& plane);

// {"unit": "lux", "planes": [{"name", "height", "spacing", "points", "min", "mean", "max",
// "uniformity_min_mean", "uniformity_min_max", "levels": [{"surface_height", ...the same}]}]}.
std::string IlluminanceJson(const std::vector<PlaneIlluminance>& planes);

}  // namespace radfarm
