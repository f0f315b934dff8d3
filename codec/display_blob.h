// A display (display/display_stage.h) as bytes: the master computes a finished job's display and
// stores it with the solution, and `radfarm fetch` writes the outputs from it without drawing it
// again. Every value is copied exactly, so the files are the bits `radfarm render` writes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "base/result.h"
#include "display/display_stage.h"

namespace radfarm::codec {

std::vector<uint8_t> EncodeDisplay(const Display& display);

// Checks the mesh is whole (one radiance per position, one patch per triangle, indices in range,
// finite values) and that it draws `patch_count` patches. Errors name the field.
Result<Display> DecodeDisplay(std::span<const uint8_t> blob, size_t patch_count);

}  // namespace radfarm::codec
