// The display mesh as `radfarm render` writes it to radiosity.ply (output/ply_writer.h): vertex
// positions and float linear radiance (radiance_r/_g/_b), and triangles. Read back here so the
// display is scored as the image shows it, with nothing shared with the solver but the file.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "core/rgb.h"
#include "core/vec3.h"

namespace radfarm::reference {

struct DisplayPly {
  std::vector<Vec3> positions;
  std::vector<Rgb> radiance;
  std::vector<std::array<uint32_t, 3>> triangles;
};

// Reads a binary little-endian PLY with exactly the writer's properties (x, y, z float; red,
// green, blue uchar; radiance_r/_g/_b float; faces as list uchar int). Errors name the file.
Result<DisplayPly> ReadDisplayPly(const std::string& path);

}  // namespace radfarm::reference
