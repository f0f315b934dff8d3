// A job bundle: what `radfarm submit` sends the master. The validated input scene (polygons and
// materials as read from the OBJ/MTL) and the job's settings with the command line's overrides
// applied, encoded as a FlatBuffer (schema/job_bundle.fbs). Meshing it (PatchMesh::Build) gives
// the same patches as `radfarm render` of the same files, so farm and embedded outputs match.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "input/input_scene.h"
#include "job/job.h"

namespace radfarm::codec {

struct JobBundle {
  Job job;
  InputScene scene;  // warnings are not carried
};

std::vector<uint8_t> EncodeJobBundle(const JobBundle& bundle);

// Verifies the buffer and every value the loaders would have checked (finite coordinates, face
// indices in range, material values in range, settings in range).
Result<JobBundle> DecodeJobBundle(std::span<const uint8_t> blob);

}  // namespace radfarm::codec
