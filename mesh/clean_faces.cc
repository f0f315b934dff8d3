#include "mesh/clean_faces.h"

#include <utility>

#include "mesh/polygon.h"

namespace radfarm {

CleanFaces CleanInputFaces(const InputScene& scene, double tol, double min_area) {
  CleanFaces out;
  for (const InputFace& input : scene.faces) {
    CleanFace face;
    face.material = input.material;
    face.line = input.line;
    face.object = input.object;
    for (uint32_t index : input.indices) face.corners.push_back(scene.positions[index]);
    RemoveRedundantCorners(tol, &face.corners);
    const Vec3 vector_area = VectorArea(face.corners);
    face.area = Length(vector_area);
    // A cleaned polygon can still have (nearly) no area, e.g. a bow-tie whose lobes cancel.
    if (face.corners.size() < 3 || !(face.area >= min_area) || face.area == 0) {
      out.degenerate_lines.push_back(input.line);
      continue;
    }
    face.normal = vector_area / face.area;
    out.faces.push_back(std::move(face));
  }
  return out;
}

}  // namespace radfarm
