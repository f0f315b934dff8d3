#include "display/corner_offsets.h"

#include <array>

namespace radfarm {

PatchCornerOffsets CornerDirectOffsets(const DisplayTopology& topology, const PatchScene& scene,
                                       const std::vector<Rgb>& irradiance,
                                       const std::vector<uint32_t>& point_of,
                                       const std::vector<Rgb>& patch_direct) {
  const std::vector<Patch>& patches = scene.patches;
  PatchCornerOffsets corners;
  corners.scene = &scene;
  corners.offsets.resize(patches.size());
  for (uint32_t f = 0; f < patches.size(); ++f) {
    const Patch& p = patches[f];
    for (uint32_t c = topology.corner_begin[f]; c < topology.corner_begin[f + 1]; ++c) {
      const uint32_t point = point_of[topology.corner_vertex[c]];
      if (point >= irradiance.size()) continue;  // no point: the offset stays 0
      // The patch's corner at this vertex (welding may have moved it by a tolerance).
      const Vec3& at = topology.corner_position[c];
      int corner = 0;
      for (int k = 1; k < p.corner_count; ++k) {
        if (Length(p.corners[k] - at) < Length(p.corners[corner] - at)) corner = k;
      }
      corners.offsets[f][corner] = p.reflectance * (irradiance[point] - patch_direct[f]);
    }
    // The mean of the offsets' interpolation (over the triangles InterpolateCornerOffsets uses).
    std::array<Rgb, 4>& o = corners.offsets[f];
    const double a1 = Length(Cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]));
    const double a2 = p.corner_count == 4
                          ? Length(Cross(p.corners[2] - p.corners[0], p.corners[3] - p.corners[0]))
                          : 0.0;
    if (!(a1 + a2 > 0)) continue;
    const Rgb mean =
        ((o[0] + o[1] + o[2]) * a1 + (o[0] + o[2] + o[3]) * a2) * (1 / (3 * (a1 + a2)));
    for (int k = 0; k < p.corner_count; ++k) o[k] = o[k] - mean;
  }
  return corners;
}

}  // namespace radfarm
