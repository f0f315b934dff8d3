// The re-bake's test and benchmark scene: a furnished room lit by eight lamps, made in code so
// that a change (a lamp dimmed, a reflectance changed) keeps every other byte, and the judge both
// use: the path-traced reference at patch centres (reference/path_tracer.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "input/input_scene.h"

namespace radfarm::bench {

struct RoomChange {
  double lamp0_scale = 1;     // lamp 0's emission times this
  Rgb wall{0.6, 0.6, 0.6};    // the walls' and ceiling's reflectance
  Rgb table{0.5, 0.35, 0.2};  // the table's
};

// A 4 x 4 x 3 room (metres, z up), its surfaces facing in; a table, a cupboard and a bed; eight
// lamps of a material each in two rows just under the ceiling.
InputScene FurnishedRoom(const RoomChange& change);

// Patch centres spread over the room's surfaces (every `stride`-th patch that does not emit) and
// the reference's radiance there, to `relative_error` (channel sum).
struct PatchReference {
  std::vector<uint32_t> patches;
  std::vector<Rgb> radiance;
  std::vector<double> relative_error;
};
PatchReference TracePatchReference(const InputScene& input, const PatchScene& patches,
                                   uint32_t stride, double relative_error, unsigned threads);

// The root mean square of a solution's relative error (channel sum) at the reference's points.
double RmsError(const std::vector<Rgb>& radiosity, const PatchReference& reference);

}  // namespace radfarm::bench
