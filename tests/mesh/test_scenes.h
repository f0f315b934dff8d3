// Hand-built InputScenes for the mesh tests (the OBJ loader is not linked here), and checks shared
// by several test files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/patch_scene.h"
#include "core/rgb.h"
#include "core/vec3.h"
#include "display/display_mesh.h"
#include "input/input_scene.h"
#include "mesh/patch_mesh.h"

namespace radfarm::testing {

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string path = "scenes/test.obj");

  // Returns the material index.
  uint32_t AddMaterial(const std::string& name, Rgb diffuse, Rgb emission = {});
  // Adds a face with its own new positions; its line is the face number counted from 1 unless
  // given. Returns the line.
  uint32_t AddFace(const std::vector<Vec3>& corners, uint32_t material = 0, uint32_t line = 0);
  // An axis-aligned box with normals out (or in, for a room), six quads.
  void AddBox(const Vec3& lo, const Vec3& hi, uint32_t material, bool normals_in = false);

  const InputScene& scene() const { return scene_; }

 private:
  InputScene scene_;
};

// A scene with one white material and these faces.
InputScene SceneOf(const std::vector<std::vector<Vec3>>& faces);

// The Cornell box from shared/reference/cornell-box.md, with the light lowered to y = 548 and the
// red wall as its published non-planar quad. Materials: white, red, green, light.
InputScene CornellBox(bool with_block_bottoms = false);

// A 4 x 4 floor at y = 0 facing up, a 0.8 x 0.8 occluder at y = 1 facing down, centred over the
// floor, and a 0.2 x 0.2 light at y = 2 facing down. From the light's edges through the occluder's
// edges, the penumbra on the floor is the band 0.7 <= |x - 2| <= 0.9 (for |z - 2| <= 0.9), and the
// same with x and z swapped: the umbra inside it, full light outside.
InputScene OccluderScene();

double TotalArea(const PatchScene& scene);
double LongestEdge(const Patch& patch);
// Value at p of the Gouraud-shaded display triangle t (barycentric interpolation in its plane).
Rgb Interpolate(const DisplayMesh& mesh, size_t t, const Vec3& p);
// Whether p lies in display triangle t (within tol of its plane and of its outline).
bool Contains(const DisplayMesh& mesh, size_t t, const Vec3& p, double tol);
// Cracks of a display mesh made from `scene`: a display vertex strictly inside an edge of a display
// triangle of the same surface (that triangle's shading does not pass through the vertex's value).
// One line per crack.
std::vector<std::string> FindCracks(const DisplayMesh& mesh, const PatchScene& scene);
// The patch triangles of `mesh` shaded with the averages of `values` (one per patch; zeros when
// empty): display/display_stage.h's AveragedDisplay.
DisplayMesh AveragedOf(const PatchMesh& mesh, std::vector<Rgb> values = {});

}  // namespace radfarm::testing
