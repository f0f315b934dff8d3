// PatchScene: the flat, library-free description of a meshed scene that the solver works on and
// that the farm ships to agents. mesh/ builds it from an input scene; nothing here knows OpenMesh.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/punctual_light.h"
#include "core/rgb.h"
#include "core/sky.h"
#include "core/vec3.h"

namespace radfarm {

// A patch's shape: all that making and tracing its rays reads (core/ray_sampler.h), and all of
// a patch an agent keeps (agent/prepared_scene.h).
struct PatchShape {
  // Corners counter-clockwise seen from the side the normal points to; corners[3] unused for
  // triangles. A quad is split into triangles (0,1,2) and (0,2,3) wherever triangles are needed.
  std::array<Vec3, 4> corners;
  uint8_t corner_count = 3;
  Vec3 normal;  // unit
  Vec3 centre;  // area centroid
};

// One radiosity patch: a planar, convex triangle or quad with constant radiosity.
struct Patch : PatchShape {
  double area = 0;
  Rgb reflectance;        // diffuse reflectance, each channel in [0, 1)
  Rgb emission;           // emitted radiance (MTL Ke units)
  uint32_t surface = 0;   // id of the smooth surface the patch belongs to (vertex averaging)
  uint32_t material = 0;  // index into PatchScene::material_names
  // One side of a two-sided surface: the other side is a patch of its own, coincident and facing
  // the other way (mesh/patch_mesh.h). Rays see such a patch only from its front, so they meet
  // the side that faces them (core/ray_caster.h).
  bool two_sided = false;
};

struct PatchScene {
  std::vector<Patch> patches;
  std::vector<std::string> material_names;
  // Lights without a surface (glTF KHR_lights_punctual), in world space: they light the patches
  // directly (core/direct_light.h) and are never hit.
  std::vector<PunctualLight> lights;
  // Light from beyond the scene (core/sky.h): rays that leave the scene upward take its luminance.
  // It lights the patches directly, as the punctual lights do (core/direct_light.h).
  Sky sky;
};

// Whether the scene has light that comes from no patch: punctual lights or a sky. Those are always
// in the direct-light start (core/direct_start.h), with their share kept apart.
inline bool HasSurfacelessLight(const PatchScene& scene) {
  return !scene.lights.empty() || scene.sky.present();
}

}  // namespace radfarm
