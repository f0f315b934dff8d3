// A unit cube with its faces' normals pointing out, as a cube modelled in Blender has, in material
// `material` (room.mtl), with a small lamp under its top if asked: seen from inside, every wall
// is lit from behind (mesh/back_face_warnings.h).
#pragma once

#include <string>

namespace radfarm::testing {

inline std::string OutwardCube(const std::string& material, bool with_lamp) {
  std::string obj =
      "mtllib room.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "usemtl " +
      material +
      "\n"
      "f 1 2 6 5\nf 4 8 7 3\nf 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\n";
  if (with_lamp) {
    obj +=
        "v 0.4 0.9 0.4\nv 0.6 0.9 0.4\nv 0.6 0.9 0.6\nv 0.4 0.9 0.6\n"
        "usemtl lamp\nf 9 10 11 12\n";
  }
  return obj;
}

}  // namespace radfarm::testing
