// A calculation plane of an illuminance report (`[[illuminance]]` in a job file): grid points at
// `height` above upward-facing surfaces, `spacing` apart (output/illuminance_grid.h).
#pragma once

#include <string>
#include <vector>

namespace radfarm {

struct IlluminancePlane {
  std::string name;    // the files' stem: illuminance/<name>.csv and .png; unique in a job
  double height = 0;   // above the surfaces, scene units (metres in glTF), >= 0
  double spacing = 0;  // between grid points, scene units, > 0
  // Shell-style patterns (fnmatch) naming the objects or materials whose upward-facing surfaces
  // carry the plane; empty: every upward-facing surface that is a floor (not furniture on one).
  std::vector<std::string> surfaces;

  bool operator==(const IlluminancePlane&) const = default;
};

// What is wrong with a plane as settings, or "" if nothing: a name that is not 1 to 64 letters,
// digits, '-', '_' or '.' (not starting with '.'; it becomes a file name), a height not finite and
// >= 0, a spacing not finite and > 0, an empty surface pattern. Shared by the job file and the job
// bundle's decoder.
std::string IlluminancePlaneProblem(const IlluminancePlane& plane);

// The most grid points one plane may hold: a plane whose spacing is far too fine for its floors is
// refused rather than computed for hours.
inline constexpr size_t kMaxIlluminancePoints = 1'000'000;

}  // namespace radfarm
