// Scenes made in code for the path-traced reference's tests: unit squares and boxes with the
// materials given, wound so that each face's front is the side named.
#pragma once

#include <array>

#include "input/input_scene.h"

namespace radfarm::reference::testing {

inline uint32_t AddMaterial(InputScene* scene, Rgb diffuse, Rgb emission, bool two_sided = false) {
  scene->materials.push_back(
      {"m" + std::to_string(scene->materials.size()), diffuse, emission, two_sided});
  return uint32_t(scene->materials.size() - 1);
}

// A quad with corners counter-clockwise about its front.
inline void AddQuad(InputScene* scene, const std::array<Vec3, 4>& corners, uint32_t material) {
  InputFace face;
  for (const Vec3& c : corners) {
    face.indices.push_back(uint32_t(scene->positions.size()));
    scene->positions.push_back(c);
  }
  face.material = material;
  scene->faces.push_back(face);
}

// The unit square [0, 1] x [0, 1] at height z, facing +z (up) or -z.
inline void AddSquareAt(InputScene* scene, double z, bool up, uint32_t material) {
  if (up) {
    AddQuad(scene, {Vec3{0, 0, z}, Vec3{1, 0, z}, Vec3{1, 1, z}, Vec3{0, 1, z}}, material);
  } else {
    AddQuad(scene, {Vec3{0, 0, z}, Vec3{0, 1, z}, Vec3{1, 1, z}, Vec3{1, 0, z}}, material);
  }
}

// The closed box [0, s]^3, every face facing in, all of one material.
inline InputScene ClosedBox(double s, Rgb diffuse, Rgb emission) {
  InputScene scene;
  scene.path = "box";
  const uint32_t m = AddMaterial(&scene, diffuse, emission);
  const Vec3 p[8] = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0},
                     {0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}};
  // Counter-clockwise seen from inside.
  AddQuad(&scene, {p[0], p[1], p[2], p[3]}, m);  // z = 0, faces +z
  AddQuad(&scene, {p[4], p[7], p[6], p[5]}, m);  // z = s, faces -z
  AddQuad(&scene, {p[0], p[4], p[5], p[1]}, m);  // y = 0, faces +y
  AddQuad(&scene, {p[3], p[2], p[6], p[7]}, m);  // y = s, faces -y
  AddQuad(&scene, {p[0], p[3], p[7], p[4]}, m);  // x = 0, faces +x
  AddQuad(&scene, {p[1], p[5], p[6], p[2]}, m);  // x = s, faces -x
  return scene;
}

}  // namespace radfarm::reference::testing
