// SceneModel: polygons with materials, as an OBJ holds them; what the generator builds and
// obj_writer.h writes. Faces are convex, counter-clockwise seen from the side they face.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace radfarm::scenegen {

struct ModelMaterial {
  std::string name;
  Vec3 reflectance;  // Kd, each in [0, 1)
  Vec3 emission;     // Ke, radiance; zero for a non-emitter
};

struct ModelFace {
  std::vector<uint32_t> vertices;  // indices into SceneModel::vertices
  uint32_t material = 0;
};

class SceneModel {
 public:
  // Returns the material's index (materials are named once).
  uint32_t AddMaterial(const ModelMaterial& material);

  // A face of the given corners (convex, counter-clockwise about its normal). Corners repeat
  // exactly where faces meet, since the coordinates are computed the same way; vertices are not
  // shared between faces (the mesher welds them).
  void AddFace(const std::vector<Vec3>& corners, uint32_t material);

  // An axis-aligned rectangle lo..hi with `axis` (0 x, 1 y, 2 z) constant (lo[axis] == hi[axis]),
  // facing +axis when `positive`, else -axis.
  void AddRectangle(const Vec3& lo, const Vec3& hi, int axis, bool positive, uint32_t material);

  // The outside of the box lo..hi without its bottom face (y = lo.y): a solid standing on a
  // surface, closed by it. Without its top face too when `open_top` (legs under a table top).
  void AddStandingBox(const Vec3& lo, const Vec3& hi, uint32_t material, bool open_top = false);

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<ModelFace>& faces() const { return faces_; }
  const std::vector<ModelMaterial>& materials() const { return materials_; }

 private:
  std::vector<Vec3> vertices_;
  std::vector<ModelFace> faces_;
  std::vector<ModelMaterial> materials_;
};

}  // namespace radfarm::scenegen
