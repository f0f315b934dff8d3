// Binary little-endian PLY of the display mesh, for MeshLab and Blender: positions, 8-bit sRGB
// vertex colours under the standard names red/green/blue, the linear radiance as extra float
// properties radiance_r/_g/_b (ignored by viewers, kept for tools), and triangles as
// "list uchar int vertex_indices".
#pragma once

#include <string>

#include "base/result.h"
#include "display/display_mesh.h"
#include "output/camera.h"

namespace radfarm {

// Colours use the image's exposure (tone_map.h). With camera.auto_exposure that means rendering
// the image to meter it; pass WithResolvedExposure(image, camera) to reuse an image already made.
// Written atomically; errors (bad indices, radiance count != vertex count) name `path`.
Status WritePly(const std::string& path, const DisplayMesh& mesh, const Camera& camera);

}  // namespace radfarm
