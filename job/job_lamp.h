// An IES lamp the job file hangs in the scene (`[[lamps]]`): its photometric file and its place.
// The job only records them; cli/job_lamps.h reads the file (input/ies_file.h) and adds the lamp
// to the scene's lights.
#pragma once

#include <string>

#include "core/vec3.h"

namespace radfarm {

struct JobLamp {
  std::string file;       // as the job file writes it: relative to the job file's directory
  std::string location;   // "job.toml:12: 'lamps[0].file'", to begin errors about the file
  Vec3 position;          // scene units (metres: the file's candela are per metre squared)
  Vec3 aim{0, -1, 0};     // the lamp's nadir axis (vertical angle 0), unit: straight down in +Y up
  double rotate = 0;      // degrees around the aim, turning horizontal angle 0 toward 90
  double multiplier = 1;  // times the file's candela, > 0
};

// The directions a lamp's horizontal angles 0 and 90 take in the scene. Unrotated, 0 lies toward
// +X (made perpendicular to the aim; toward -Z when the aim is along X) and 90 along
// Cross(zero, aim): counter-clockwise seen from above a lamp aimed down, as LM-63 turns them.
// `rotate` turns 0 toward 90.
Vec3 LampReference(const JobLamp& lamp);

}  // namespace radfarm
