// A floor for the lightmap tests: the unit square in the xz plane (object 0), input as two
// triangles whose lightmap UV is (x / 2, z / 2), displayed as four triangles around its centre,
// front and back (a two-sided surface); a second object with no lightmap UV.
#pragma once

#include <vector>

#include "display/display_mesh.h"
#include "input/input_scene.h"

namespace radfarm {

struct LightmapTestScene {
  DisplayMesh mesh;
  std::vector<uint32_t> patch_object;  // by patch (one patch per display triangle)
  std::vector<LightmapTriangle> input;
  std::vector<InputObject> objects;

  // front/back: the radiance of the floor's front (facing -y, as the input) and back vertices.
  LightmapTestScene(const Rgb& front, const Rgb& back) {
    const Vec3 c{0.5, 0, 0.5}, a{0, 0, 0}, b{1, 0, 0}, d{1, 0, 1}, e{0, 0, 1};
    input.push_back({0, {a, b, d}, {Uv{0, 0}, Uv{0.5f, 0}, Uv{0.5f, 0.5f}}});
    input.push_back({0, {a, d, e}, {Uv{0, 0}, Uv{0.5f, 0.5f}, Uv{0, 0.5f}}});
    mesh.positions = {c, a, b, d, e, c, a, b, d, e, {5, 5, 5}, {6, 5, 5}, {5, 6, 5}};
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < 5; ++k) mesh.radiance.push_back(side == 0 ? front : back);
      const uint32_t o = side * 5;
      for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t p = o + 1 + k, q = o + 1 + (k + 1) % 4;
        // Front: the input's winding (normal -y); back: reversed.
        mesh.triangles.push_back(side == 0 ? std::array<uint32_t, 3>{o, p, q}
                                           : std::array<uint32_t, 3>{o, q, p});
      }
    }
    for (int k = 0; k < 3; ++k) mesh.radiance.push_back(Rgb(9, 9, 9));
    mesh.triangles.push_back({10, 11, 12});
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) mesh.triangle_patch.push_back(t);
    patch_object.assign(8, 0);
    patch_object.push_back(1);
    InputObject floor, other;
    floor.name = "floor";
    other.name = "other";
    objects = {floor, other};
  }
};

}  // namespace radfarm
