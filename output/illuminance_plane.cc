#include "output/illuminance_plane.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace radfarm {

std::string IlluminancePlaneProblem(const IlluminancePlane& plane) {
  const std::string& name = plane.name;
  const bool name_ok = !name.empty() && name.size() <= 64 && name.front() != '.' &&
                       std::all_of(name.begin(), name.end(), [](unsigned char c) {
                         return std::isalnum(c) || c == '-' || c == '_' || c == '.';
                       });
  if (!name_ok)
    return "name must be 1 to 64 letters, digits, '-', '_' or '.', not starting with '.'";
  if (!std::isfinite(plane.height) || plane.height < 0) return "height must be finite and >= 0";
  if (!std::isfinite(plane.spacing) || !(plane.spacing > 0))
    return "spacing must be finite and > 0";
  for (const std::string& pattern : plane.surfaces) {
    if (pattern.empty()) return "surfaces must not hold an empty pattern";
  }
  return "";
}

}  // namespace radfarm
