// A job's work plane solved as `radfarm render` solves it, against the path tracer at the same
// grid points: what the illuminance accuracy tests share.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli/job_inputs.h"
#include "output/illuminance_planes.h"
#include "reference/path_tracer.h"

namespace radfarm::testing {

struct PlaneAgainstReference {
  std::optional<LoadedJob> job;  // empty where it failed to load
  std::vector<double> lux;                          // the report's, at the plane's grid points
  std::vector<reference::PointEstimate> reference;  // the path tracer's, at the same points
};

// Solves `job_file` and measures `plane` (which must have at least `min_points`) and the path
// tracer's irradiance at its points; failures are the test's.
PlaneAgainstReference MeasureAgainstReference(const std::string& job_file,
                                              const IlluminancePlane& plane, size_t min_points,
                                              const reference::TraceSettings& settings);

// Expects every point within three of the reference's standard errors and 5 % of the report's
// own, and a mean relative error within 3 %; returns the points' absolute relative errors, sorted.
std::vector<double> ExpectWithinReference(const PlaneAgainstReference& measured);

}  // namespace radfarm::testing
