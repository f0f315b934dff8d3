// What every scene the readers accept must satisfy, whatever the file said: the fuzzers abort (a
// finding) when an accepted scene breaks it.
#pragma once

#include "input/input_scene.h"

namespace radfarm::fuzz {

// Faces of 3 or more corners, indices in range, finite positions, materials and objects in range,
// parents before children.
void CheckLoadedScene(const InputScene& scene);

}  // namespace radfarm::fuzz
