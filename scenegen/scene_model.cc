#include "scenegen/scene_model.h"

#include <algorithm>
#include <cassert>

namespace radfarm::scenegen {
namespace {

Vec3 WithAxis(Vec3 v, int axis, double value) {
  (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = value;
  return v;
}

}  // namespace

uint32_t SceneModel::AddMaterial(const ModelMaterial& material) {
  for (uint32_t i = 0; i < materials_.size(); ++i) {
    if (materials_[i].name == material.name) return i;
  }
  materials_.push_back(material);
  return static_cast<uint32_t>(materials_.size() - 1);
}

void SceneModel::AddFace(const std::vector<Vec3>& corners, uint32_t material) {
  ModelFace face;
  face.material = material;
  for (const Vec3& c : corners) {
    face.vertices.push_back(static_cast<uint32_t>(vertices_.size()));
    vertices_.push_back(c);
  }
  faces_.push_back(std::move(face));
}

void SceneModel::AddRectangle(const Vec3& lo, const Vec3& hi, int axis, bool positive,
                              uint32_t material) {
  assert(lo[axis] == hi[axis]);
  // The two other axes in cyclic order (u, v, axis) are right-handed: u x v = +axis.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double level = lo[axis];
  auto at = [&](double a, double b) {
    Vec3 p = WithAxis(Vec3{}, axis, level);
    p = WithAxis(p, u, a);
    return WithAxis(p, v, b);
  };
  std::vector<Vec3> corners = {at(lo[u], lo[v]), at(hi[u], lo[v]), at(hi[u], hi[v]),
                               at(lo[u], hi[v])};
  if (!positive) std::reverse(corners.begin(), corners.end());
  AddFace(corners, material);
}

void SceneModel::AddStandingBox(const Vec3& lo, const Vec3& hi, uint32_t material, bool open_top) {
  AddRectangle({lo.x, lo.y, lo.z}, {lo.x, hi.y, hi.z}, 0, false, material);
  AddRectangle({hi.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}, 0, true, material);
  AddRectangle({lo.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, 2, false, material);
  AddRectangle({lo.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, 2, true, material);
  if (!open_top) AddRectangle({lo.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, 1, true, material);
}

}  // namespace radfarm::scenegen
